//! [`GelTip`]: the GelTip finger-shaped tactile sensor (Gomes, Lin and Luo, IROS 2020) in the
//! world.

use yarok_core::component::Declaration;

use super::component::{Tactile, TactileKind};
use super::kind::{Optics, SensorConfig, SensorKind};
use crate::tactile::SizeError;
use crate::tactile::calibration::Calibration;
use crate::tactile::elastomer::Elastomer;
use crate::tactile::geltip::{GelTipModel, GelTipParams};
use crate::tactile::light_fields::{LightFieldMethod, led_ring};

/// Image columns and rows, and the camera's vertical field of view (degrees).
const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;
const FOVY: f64 = 70.0;

/// The membrane's outer surface (metres, along the axis from the camera): a tube of this radius
/// from `START`, closed by a dome whose top is at `TIP`.
const RADIUS: f64 = 0.015;
const START: f64 = 0.005;
const TIP: f64 = 0.045;

/// The elastomer's thickness: the deepest a press can go.
const THICKNESS: f64 = 0.004;

/// The LEDs: three on a 12.6 mm ring around the camera, in its plane.
const LED_RADIUS: f64 = 0.0126;

/// The GelTip's geometry and model.
struct Kind;

const GELTIP: Kind = Kind;

impl Kind {
    /// The untouched membrane's depth along the camera axis, pixel by pixel: where each pixel's
    /// ray meets the tube, or the dome beyond it.
    fn membrane() -> Vec<f32> {
        let f = f64::from(HEIGHT) / (2.0 * (FOVY.to_radians() / 2.0).tan());
        let (cx, cy) = (
            (f64::from(WIDTH) - 1.0) / 2.0,
            (f64::from(HEIGHT) - 1.0) / 2.0,
        );
        let dome = TIP - RADIUS;
        let mut depth = Vec::with_capacity((WIDTH * HEIGHT) as usize);
        for v in 0..HEIGHT {
            for u in 0..WIDTH {
                let spread = ((f64::from(u) - cx) / f).hypot((f64::from(v) - cy) / f);
                let tube = if spread > 0.0 {
                    RADIUS / spread
                } else {
                    f64::INFINITY
                };
                let along = if tube <= dome {
                    tube.max(START)
                } else {
                    // The far root of |t·(a, b, 1) − (0, 0, dome)| = RADIUS.
                    let scale = spread * spread + 1.0;
                    let reach = RADIUS * RADIUS - spread * spread * (dome * dome - RADIUS * RADIUS);
                    (dome + reach.max(0.0).sqrt()) / scale
                };
                depth.push(along as f32);
            }
        }
        depth
    }
}

/// The membrane's and the camera's geometry the GelTip model is made for: template values that
/// cannot be set.
#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GelTipGeometry {
    /// The tube's radius, and where along the axis the membrane starts and ends (metres).
    radius: f64,
    start: f64,
    tip: f64,
    /// The base camera's vertical field of view (degrees).
    fovy: f64,
}

/// The geometry the GelTip model is made for.
pub(super) fn geometry() -> GelTipGeometry {
    GelTipGeometry {
        radius: RADIUS,
        start: START,
        tip: TIP,
        fovy: FOVY,
    }
}

impl SensorKind for Kind {
    fn gel(&self) -> &'static str {
        "membrane"
    }

    fn elastomer(&self) -> Elastomer {
        Elastomer::GELTIP
    }

    fn fovy(&self) -> f64 {
        FOVY
    }

    fn declaration(&self) -> Declaration {
        Declaration::new("geltip")
            .config(SensorConfig::new(30.0, false, "none"))
            .config(geometry())
            .template(include_str!("geltip.xml"))
    }

    fn size(&self) -> (u32, u32) {
        (WIDTH, HEIGHT)
    }

    fn reach(&self) -> f64 {
        TIP.hypot(RADIUS)
    }

    fn optics(
        &self,
        _seed: u64,
        _noise: bool,
        calibration: Option<Calibration>,
    ) -> Result<Box<dyn Optics>, String> {
        if calibration.is_some() {
            return Err("a calibration models a flat gel; the GelTip's is a tube".into());
        }
        let membrane = Self::membrane();
        let params = GelTipParams {
            fov_deg: FOVY,
            clamp_diffuse: true,
            ..GelTipParams::default()
        };
        let leds = led_ring(params.lights.len(), LED_RADIUS, 0.0);
        let model = GelTipModel::from_geometry(
            params,
            &membrane,
            WIDTH as usize,
            &leds,
            LightFieldMethod::Plane,
        )
        .map_err(|error| error.to_string())?;
        let f = f64::from(HEIGHT) / (2.0 * (FOVY.to_radians() / 2.0).tan());
        let mean = membrane.iter().map(|d| f64::from(*d)).sum::<f64>() / membrane.len() as f64;
        Ok(Box::new(GelTipOptics {
            model,
            membrane,
            pixel_area: (mean / f) * (mean / f),
        }))
    }
}

/// The membrane and the GelTip model over it.
struct GelTipOptics {
    model: GelTipModel,
    membrane: Vec<f32>,
    /// The mean area a pixel covers on the membrane.
    pixel_area: f64,
}

impl Optics for GelTipOptics {
    fn surface(&self) -> &[f32] {
        &self.membrane
    }

    fn thickness(&self) -> f64 {
        THICKNESS
    }

    fn pixel_area(&self) -> f64 {
        self.pixel_area
    }

    fn surface_distance(&self, x: f64, y: f64) -> Option<f64> {
        let across = x.hypot(y);
        (across < RADIUS).then(|| TIP - RADIUS + (RADIUS * RADIUS - across * across).sqrt())
    }

    fn render(
        &mut self,
        depth: &[f32],
        background: &[u8],
        out: &mut [u8],
    ) -> Result<(), SizeError> {
        self.model.render_into(depth, background, out)
    }

    #[cfg(feature = "parallel")]
    fn set_parallel(&mut self, parallel: bool) {
        self.model.set_parallel(parallel);
    }
}

/// A GelTip finger-shaped tactile sensor (a [`TactileSensor`](super::TactileSensor): `read()`, `read_depth()`,
/// `contact()`): a 30 mm tube with a domed tip, 45 mm long, sensing all over; 320 × 240
/// frames at 30 fps from the GelTip model (light fields computed from this geometry, the
/// "plane" method, diffuse light clamped) over the depth its base camera (70°) renders.
///
/// Tag `geltip`; config `pos` and `quat` (placement; its axis is +z), `fps`, `parallel` (its
/// model across threads), `calibration` (only `"none"`: calibrations model flat gels). The
/// model has no texture noise, so `noise` changes nothing; the
/// membrane's and camera's geometry (`radius`, `start`, `tip`, `fovy`) is the model's and
/// cannot be set.
///
/// Environments: `sim`; `mock` (always the untouched membrane); `real` (feature `camera`): the
/// sensor's camera (interface settings as [`Cam`](crate::cameras::Cam)'s: `device`, e.g.
/// `/dev/video0`, `command` or `file`), its frames as they come; no depth or contact
/// measures.
pub type GelTip = Tactile<GelTipKind>;

/// The GelTip, as a [`TactileKind`].
#[derive(Debug, Clone, Copy)]
pub struct GelTipKind;

impl TactileKind for GelTipKind {
    const NAME: &'static str = "GelTip";
    type Geometry = GelTipGeometry;

    fn kind() -> &'static dyn SensorKind {
        &GELTIP
    }

    fn geometry() -> GelTipGeometry {
        geometry()
    }
}
