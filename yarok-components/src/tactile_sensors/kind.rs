//! [`SensorKind`]: what one kind of tactile sensor is — its declaration, image, gel and
//! optics — and the config every kind shares (frame rate, calibration, fixed geometry).

use serde::Serialize;
use serde::de::DeserializeOwned;
use yarok_core::component::{Bind, BindError, Declaration, Environment};
use yarok_core::value::Config;

use crate::tactile::SizeError;
use crate::tactile::calibration::Calibration;
use crate::tactile::elastomer::Elastomer;

/// The optical side of one kind of sensor: the untouched gel as its camera sees it, and the
/// model that makes the image.
pub trait Optics {
    /// The untouched gel's depth (metres along the camera axis) pixel by pixel, row-major: what
    /// the camera sees when nothing presses, and how far it sees.
    fn surface(&self) -> &[f32];
    /// The gel's thickness (metres): the deepest a press can go.
    fn thickness(&self) -> f64;
    /// The area (square metres) a pixel covers on the gel.
    fn pixel_area(&self) -> f64;
    /// How far (metres, along the sensor's axis from its camera) the untouched gel's outer
    /// surface is at `(x, y)` metres across the axis, if the gel is there.
    fn surface_distance(&self, x: f64, y: f64) -> Option<f64>;
    /// The image of the gel at `depth` (clamped to the untouched surface) over `background`.
    ///
    /// # Errors
    ///
    /// When the sizes do not match the model's.
    fn render(&mut self, depth: &[f32], background: &[u8], out: &mut [u8])
    -> Result<(), SizeError>;
    /// Splits each image's work across rayon's threads (`true`) or not.
    #[cfg(feature = "parallel")]
    fn set_parallel(&mut self, parallel: bool);
}

/// The config every kind of sensor has.
#[derive(Serialize, serde::Deserialize)]
pub(super) struct SensorConfig {
    /// Where it is and how it is turned in its parent's frame.
    pos: [f64; 3],
    quat: [f64; 4],
    /// Frames per second.
    fps: f64,
    /// Whether its model splits each image across threads.
    parallel: bool,
    /// Whether the image has the gel's texture noise.
    noise: bool,
    /// The optical model: `"none"`, `"bundled"` or a calibration file.
    calibration: String,
}

impl SensorConfig {
    /// Placed at its parent's origin, as its parent's frame is turned.
    pub(super) fn new(fps: f64, noise: bool, calibration: &str) -> Self {
        Self {
            pos: [0.0; 3],
            quat: [1.0, 0.0, 0.0, 0.0],
            fps,
            parallel: cfg!(feature = "parallel"),
            noise,
            calibration: calibration.to_owned(),
        }
    }

    /// The configured frame rate, a positive number.
    pub(super) fn frame_rate<E: Environment>(&self, bind: &Bind<E>) -> Result<f64, BindError> {
        let fps = self.fps;
        if !(fps > 0.0 && fps.is_finite()) {
            return Err(bind.error(format!("fps must be a positive number, not {fps}")));
        }
        Ok(fps)
    }

    /// The calibration `calibration` names: `"none"` (the reference model), `"bundled"` (the
    /// kind's own) or a calibration file.
    pub(super) fn calibration<E: Environment>(
        &self,
        kind: &dyn SensorKind,
        bind: &Bind<E>,
    ) -> Result<Option<Calibration>, BindError> {
        match self.calibration.as_str() {
            "none" => Ok(None),
            "bundled" => kind.bundled_calibration().map(Some).ok_or_else(|| {
                bind.error("calibration = \"bundled\", but this sensor has no bundled calibration")
            }),
            path => {
                let calibration = Calibration::load(path)
                    .map_err(|e| bind.error(format!("calibration = {path:?}: {e}")))?;
                calibration
                    .check_sensor(kind.declaration().tag())
                    .map_err(|e| bind.error(format!("calibration = {path:?}: {e}")))?;
                Ok(Some(calibration))
            }
        }
    }

    /// Whether its model splits each image across threads.
    pub(super) fn parallel(&self) -> bool {
        self.parallel
    }

    /// Whether the image has the gel's texture noise.
    pub(super) fn noise(&self) -> bool {
        self.noise
    }
}

/// One kind of sensor: its component's declaration, image size and optics.
pub trait SensorKind {
    fn declaration(&self) -> Declaration;
    /// The template's name for the gel's geom: what presses on it is what the sensor feels.
    #[cfg_attr(not(feature = "render"), allow(dead_code))]
    fn gel(&self) -> &'static str;
    /// How deep the gel sinks under a normal force.
    fn elastomer(&self) -> Elastomer;
    /// The internal camera's vertical field of view (degrees).
    fn fovy(&self) -> f64;
    /// Image columns and rows.
    fn size(&self) -> (u32, u32);
    /// Whether the real sensor's camera lies across the image: its landscape frames are turned
    /// to the image's portrait as digit-interface's `get_frame` does (transposed, then flipped
    /// upside down).
    #[cfg(feature = "camera")]
    fn turned(&self) -> bool {
        false
    }
    /// The farthest any point of the untouched gel lies from the camera (metres): nothing
    /// beyond it can show in the image.
    #[cfg_attr(not(feature = "render"), allow(dead_code))]
    fn reach(&self) -> f64;
    /// The calibration its `calibration = "bundled"` names, if it has one.
    fn bundled_calibration(&self) -> Option<Calibration> {
        None
    }
    /// The optics, with the gel's texture noise seeded by `seed` (none when `noise` is off):
    /// the `calibration`'s model if one is given, else the reference model.
    ///
    /// # Errors
    ///
    /// When the model cannot be made for this geometry (or calibration).
    fn optics(
        &self,
        seed: u64,
        noise: bool,
        calibration: Option<Calibration>,
    ) -> Result<Box<dyn Optics>, String>;
}

/// Refuses config that changes the geometry the optical model is made for: `fixed`, a struct
/// of the gel's and the camera's dimensions.
pub(super) fn check_geometry<G, E>(bind: &Bind<E>, fixed: &G) -> Result<(), BindError>
where
    G: Serialize + DeserializeOwned + PartialEq,
    E: Environment,
{
    let set: G = bind.config()?;
    if set == *fixed {
        return Ok(());
    }
    let values = |geometry: &G| Config::from_fields(geometry).map_err(|e| bind.error(e));
    let (set, fixed) = (values(&set)?, values(fixed)?);
    let changed = fixed
        .iter()
        .find(|(key, value)| set.get(key) != Some(value));
    let (key, value) = changed.ok_or_else(|| bind.error("the gel's geometry differs"))?;
    let given = set.get(key).map(ToString::to_string).unwrap_or_default();
    Err(bind.error(format!(
        "{key} = {given}, but the optical model is made for {value}: the gel's and the \
         camera's geometry cannot be changed"
    )))
}
