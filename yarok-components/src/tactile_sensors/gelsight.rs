//! [`GelSight2014`]: the 2014 GelSight fingertip sensor (Li et al., IROS 2014) in the world.

use super::component::{Tactile, TactileKind};
use super::kind::SensorKind;
use super::phong::{FlatGelGeometry, Spec};
use crate::tactile::elastomer::Elastomer;
use crate::tactile::phong::PhongParams;

/// The GelSight 2014 fingertip: 640 × 480 frames at 30 fps, a 4 mm gel 34 mm in front of its
/// camera (a field of 34.8 × 26.1 mm at the model's 54.3 µm a pixel), 40 × 30 × 34 mm.
const GELSIGHT_2014: Spec = Spec {
    tag: "gelsight2014",
    width: 640,
    height: 480,
    gel_face: 0.034,
    thickness: 0.004,
    housing: [0.02, 0.015],
    gel: [0.0175, 0.0131],
    model: PhongParams::gelsight2014,
    elastomer: Elastomer::GELSIGHT2014,
    bundled: None,
    fps: 30.0,
    #[cfg(feature = "camera")]
    turned: false,
};

/// A GelSight 2014 fingertip tactile sensor (a [`TactileSensor`](super::TactileSensor): `read()`, `read_depth()`,
/// `contact()`).
///
/// Tag `gelsight2014`; config `pos` and `quat` (placement; it senses along its +z), `fps`
/// (default 30), `noise` (the gel's texture, default on, seeded from the platform's seed),
/// `parallel` (its model across threads), `housing` (half sizes, m), `calibration` (the
/// optical model: `"none"`, the default, the reference Phong model; or a 640 × 480
/// calibration file written by `yarok tactile calibrate`). The gel's and camera's
/// geometry (`gel_face`, `thickness`, `gel`, `fovy`) is the optical model's and cannot be
/// set.
///
/// Environments: `sim`; `mock` (always the untouched gel); `real` (feature `camera`): the
/// sensor's camera (interface settings as [`Cam`](crate::cameras::Cam)'s: `device`, e.g.
/// `/dev/video0`, `command` or `file`), its frames as they come; no depth or contact
/// measures.
pub type GelSight2014 = Tactile<GelSight2014Kind>;

/// The GelSight 2014 fingertip sensor, as a [`TactileKind`].
#[derive(Debug, Clone, Copy)]
pub struct GelSight2014Kind;

impl TactileKind for GelSight2014Kind {
    const NAME: &'static str = "GelSight2014";
    type Geometry = FlatGelGeometry;

    fn kind() -> &'static dyn SensorKind {
        &GELSIGHT_2014
    }

    fn geometry() -> FlatGelGeometry {
        GELSIGHT_2014.geometry()
    }
}
