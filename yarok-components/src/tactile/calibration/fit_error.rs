//! [`FitError`] and [`SettingError`]: why presses and settings cannot be fitted into a
//! calibration.

use super::{Area, PlacementOutOfRange};

/// Why a calibration cannot be fitted (or made from its parts).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FitError {
    /// A sensor's name that cannot name a calibration.
    #[error("sensor {0:?} is not a sensor's name (letters, digits, _ and -, at most 64)")]
    SensorName(String),
    /// No press was given.
    #[error("no presses to fit to")]
    NoPresses,
    /// A press's frame is not the size of the untouched frame.
    #[error(
        "press {press}'s frame is {}×{}, the untouched frame {}×{}",
        size[0],
        size[1],
        untouched[0],
        untouched[1]
    )]
    FrameSize {
        /// The press's index.
        press: usize,
        /// Its frame's width and height.
        size: [u32; 2],
        /// The untouched frame's width and height.
        untouched: [u32; 2],
    },
    /// A press's centre or radius is not a number, or its radius not positive.
    #[error("press {press} has no finite centre and positive radius")]
    PressShape {
        /// The press's index.
        press: usize,
    },
    /// A setting is given no value to try.
    #[error("no {setting} to try")]
    NothingToTry {
        /// The setting's name.
        setting: &'static str,
    },
    /// A setting's value is not physical.
    #[error(transparent)]
    Setting(#[from] SettingError),
    /// Every contact scale tried makes the widest press's circle wider than the ball.
    #[error(
        "with contact scale {} the widest press's contact circle ({widest_pixels} px × the scale) \
         is wider than the {ball_diameter_mm} mm ball ({:.1} px at {pixels_per_mm} px/mm): a \
         ball cannot touch a circle wider than itself; these presses allow a contact scale of at \
         most {:.3}",
        tried.iter().map(f64::to_string).collect::<Vec<_>>().join(", "),
        ball_radius_pixels,
        ball_radius_pixels / widest_pixels
    )]
    ContactWiderThanBall {
        /// The contact scales tried.
        tried: Vec<f64>,
        /// The widest press's radius (pixels).
        widest_pixels: f64,
        /// The ball's diameter (millimetres).
        ball_diameter_mm: f64,
        /// The ball's radius (pixels).
        ball_radius_pixels: f64,
        /// The image's scale.
        pixels_per_mm: f64,
    },
    /// The imprints, fitted, lie beyond any plausible placement of the described centres.
    #[error(
        "the presses' imprints lie far from their described centres ({0}): are the centres the \
         frames' own, in pixels?"
    )]
    FarFromCentres(PlacementOutOfRange),
    /// The presses do not determine the model's coefficients.
    #[error("the presses do not determine the model")]
    Undetermined,
    /// A covered area that is not a rectangle.
    #[error("the covered area {0:?} is not a rectangle")]
    NotARectangle(Area),
    /// Noise levels that are not finite and non-negative.
    #[error("the noise levels {0:?} are not finite and non-negative")]
    Noise([f64; 3]),
    /// The wrong number of coefficients, or coefficients that are not finite.
    #[error("{needed} coefficients (finite) are needed, not {given}")]
    Coefficients {
        /// How many the model has.
        needed: usize,
        /// How many were given.
        given: usize,
    },
}

/// A calibration setting that is not one, or whose value is outside its physical range
/// ([`SETTING_RANGES`](super::SETTING_RANGES)).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SettingError {
    /// No calibration setting has this name.
    #[error("{0} is no calibration setting")]
    Unknown(String),
    /// The value is outside the setting's range.
    #[error("{name} {} is outside its physical range, {lowest} to {highest}", shown(*value))]
    OutOfRange {
        /// The setting's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The range's lowest value.
        lowest: f64,
        /// The range's highest value.
        highest: f64,
    },
}

/// `value` as a person reads it: in scientific notation when very large or small.
fn shown(value: f64) -> String {
    if value.abs() >= 1e6 || (value != 0.0 && value.abs() < 1e-3) {
        format!("{value:e}")
    } else {
        value.to_string()
    }
}
