//! [`SensorKind`]: what one kind of tactile sensor is — its declaration, image, gel and
//! optics — and the config every kind shares (frame rate, calibration, fixed geometry).

use yarok_core::component::{Bind, BindError, Declaration, Environment};

use crate::tactile::SizeError;
use crate::tactile::calibration::Calibration;
use crate::tactile::elastomer::Elastomer;

/// The optical side of one kind of sensor: the untouched gel as its camera sees it, and the
/// model that makes the image.
pub(super) trait Optics {
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

/// One kind of sensor: its component's declaration, image size and optics.
pub(super) trait SensorKind {
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
    /// The config keys the optical model fixes (the gel's and the camera's geometry), with
    /// their values.
    fn geometry(&self) -> Vec<(&'static str, Vec<f64>)>;
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

/// The configured frame rate, a positive number.
pub(super) fn frame_rate<E: Environment>(bind: &Bind<E>) -> Result<f64, BindError> {
    let fps: f64 = bind.config_value("fps")?;
    if !(fps > 0.0 && fps.is_finite()) {
        return Err(bind.error(format!("fps must be a positive number, not {fps}")));
    }
    Ok(fps)
}

/// The calibration the config's `calibration` names: `"none"` (the reference model),
/// `"bundled"` (the kind's own) or a calibration file.
pub(super) fn calibration<E: Environment>(
    kind: &dyn SensorKind,
    bind: &Bind<E>,
) -> Result<Option<Calibration>, BindError> {
    let named: String = bind.config_value("calibration")?;
    match named.as_str() {
        "none" => Ok(None),
        "bundled" => kind.bundled_calibration().map(Some).ok_or_else(|| {
            bind.error("calibration = \"bundled\", but this sensor has no bundled calibration")
        }),
        path => Calibration::load(path)
            .map(Some)
            .map_err(|e| bind.error(format!("calibration = {path:?}: {e}"))),
    }
}

/// Refuses config that changes the geometry the optical model is made for.
pub(super) fn check_geometry<E: Environment>(
    kind: &dyn SensorKind,
    bind: &Bind<E>,
) -> Result<(), BindError> {
    for (key, fixed) in kind.geometry() {
        let set: Vec<f64> = match fixed.len() {
            1 => vec![bind.config_value::<f64>(key)?],
            _ => bind.config_value(key)?,
        };
        let same = set.len() == fixed.len()
            && set
                .iter()
                .zip(&fixed)
                .all(|(set, fixed)| (set - fixed).abs() <= 1e-12 * fixed.abs().max(1.0));
        if !same {
            return Err(bind.error(format!(
                "{key} = {set:?}, but the optical model is made for {fixed:?}: the gel's and the \
                 camera's geometry cannot be changed"
            )));
        }
    }
    Ok(())
}
