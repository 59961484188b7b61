//! [`Digit`]: the DIGIT tactile sensor (Lambeta et al., 2020) in the world.

use super::component::{Tactile, TactileKind};
use super::kind::SensorKind;
use super::phong::{FlatGelGeometry, Spec};
use crate::tactile::calibration::Calibration;
use crate::tactile::elastomer::Elastomer;
use crate::tactile::phong::PhongParams;

/// The DIGIT: 240 × 320 frames (portrait QVGA) at 60 fps, a 2 mm gel 18 mm in front of its
/// camera (a field of 13.0 × 17.4 mm), 27 × 20 × 18 mm.
const DIGIT: Spec = Spec {
    tag: "digit",
    width: 240,
    height: 320,
    gel_face: 0.018,
    thickness: 0.002,
    housing: [0.0135, 0.01],
    gel: [0.0095, 0.008],
    model: PhongParams::digit_metric,
    elastomer: Elastomer::DIGIT,
    bundled: Some(Calibration::digit),
    fps: 60.0,
    #[cfg(feature = "camera")]
    turned: true,
};

/// A DIGIT tactile sensor (a [`TactileSensor`](super::TactileSensor): `read()`, `read_depth()`, `contact()`).
///
/// Tag `digit`; config `pos` and `quat` (placement; it senses along its +z), `fps` (default 60,
/// the DIGIT's QVGA rate), `noise` (default on, seeded from the platform's seed: with the
/// calibration, a fixed pattern of the real camera's noise as it measured it; with the
/// reference model, the gel's texture), `parallel` (its model across threads), `housing` (half
/// sizes, m), `calibration` (the optical model: `"bundled"`, the default, fitted to a real
/// DIGIT's frames, [`Calibration::digit`]; `"none"`, the reference Phong model; or a
/// calibration file written by `yarok tactile calibrate`). Mount it on a
/// gripper pad with `parent=` and a `quat` that turns +z inward. The gel's and camera's
/// geometry (`gel_face`, `thickness`, `gel`, `fovy`) is the optical model's and cannot be
/// set.
///
/// Environments: `sim`; `mock` (always the untouched gel); `real` (feature `camera`): the
/// DIGIT's camera (interface settings as [`Cam`](crate::cameras::Cam)'s: `device`, e.g.
/// `/dev/video0`, `command` or `file`; its QVGA stream, 320 × 240 at `fps`, or the VGA one
/// with `size = [640, 480]` and `fps = 30`), each frame turned to portrait as
/// digit-interface's `get_frame` does; no depth or contact measures.
pub type Digit = Tactile<DigitKind>;

/// The DIGIT, as a [`TactileKind`].
#[derive(Debug, Clone, Copy)]
pub struct DigitKind;

impl TactileKind for DigitKind {
    const NAME: &'static str = "Digit";
    type Geometry = FlatGelGeometry;

    fn kind() -> &'static dyn SensorKind {
        &DIGIT
    }

    fn geometry() -> FlatGelGeometry {
        DIGIT.geometry()
    }
}
