//! Optical tactile sensor models: from the depth map a camera inside the sensor sees, to the
//! image the sensor produces. Pure image computation, no MuJoCo.
//!
//! - [`phong`]: the Phong model of DIGIT and GelSight (elastic deformation by a difference of
//!   Gaussians, internal shadow, coloured lights, final blur).
//! - [`geltip`]: the GelTip model (elastic deformation, back-projection, light fields).
//! - [`light_fields`]: GelTip light fields computed from the sensor geometry (linear, plane).
//!
//! Images are row-major, top row first; colours RGB. Output sizes: DIGIT 320 rows × 240 columns,
//! GelSight 480 × 640, GelTip 240 × 320 (the input depth's size).

pub mod calibration;
pub mod elastomer;
pub mod fidelity;
mod field;
pub mod filter;
pub mod geltip;
pub mod light_fields;
pub mod noise;
pub mod npy;
pub mod phong;
mod rows;
mod surface;

yarok_core::debug_as_report!(SizeError);

/// An input whose size does not fit the image being rendered.
#[derive(Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SizeError {
    /// The depth map is not a whole number of rows of the given width.
    #[error("a depth map of {len} values is not a whole number of rows of {width}")]
    NotWholeRows {
        /// Values in the depth map.
        len: usize,
        /// The width given.
        width: usize,
    },
    /// An input or output holds the wrong number of values.
    #[error("the {what} holds {actual} values; a {width} × {height} image needs {expected}")]
    Mismatch {
        /// Which input or output.
        what: &'static str,
        /// Values it holds.
        actual: usize,
        /// Values it should hold.
        expected: usize,
        /// The image's width.
        width: usize,
        /// The image's height.
        height: usize,
    },
    /// The model's lights and the light fields (or LEDs) given for them differ in number.
    #[error("{lights} lights but {fields} light fields or LEDs")]
    LightCount {
        /// Lights in the parameters.
        lights: usize,
        /// Light fields or LEDs given.
        fields: usize,
    },
}

/// The height of a depth map of `len` values, `width` wide.
fn image_height(len: usize, width: usize) -> Result<usize, SizeError> {
    if width == 0 || !len.is_multiple_of(width) {
        return Err(SizeError::NotWholeRows { len, width });
    }
    Ok(len / width)
}

/// Checks that `what` holds `channels` values per pixel of a `width × height` image.
pub(crate) fn expect_len(
    what: &'static str,
    actual: usize,
    channels: usize,
    (width, height): (usize, usize),
) -> Result<(), SizeError> {
    let expected = channels * width * height;
    if actual != expected {
        return Err(SizeError::Mismatch {
            what,
            actual,
            expected,
            width,
            height,
        });
    }
    Ok(())
}

/// `base` to an integer power by repeated squaring (odd powers keep the sign), without the
/// library call `powi` becomes for a run-time exponent.
fn int_pow(base: f64, exponent: i32) -> f64 {
    let (mut result, mut square, mut n) = (1.0, base, exponent.unsigned_abs());
    while n > 0 {
        if n & 1 == 1 {
            result *= square;
        }
        square *= square;
        n >>= 1;
    }
    if exponent < 0 { 1.0 / result } else { result }
}

/// A smooth default background (`height × width × 3`, RGB) for sensors without a photograph of
/// their own: a soft vertical gradient with a brighter centre, like an evenly lit gel.
pub fn default_background(width: usize, height: usize) -> Vec<u8> {
    let mut image = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for x in 0..width {
            let (u, v) = (
                x as f64 / width.max(2) as f64 - 0.5,
                y as f64 / height.max(2) as f64 - 0.5,
            );
            let light = 1.0 - 0.6 * (u * u + v * v);
            for (base, tilt) in [(120.0, 20.0), (125.0, 0.0), (130.0, -20.0)] {
                image.push(((base + tilt * v) * light).clamp(0.0, 255.0) as u8);
            }
        }
    }
    image
}
