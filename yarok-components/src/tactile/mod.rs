//! Optical tactile sensor models: from the depth map a camera inside the sensor sees, to the
//! image the sensor produces. Pure image computation, no MuJoCo.
//!
//! - [`phong`]: the Phong model of DIGIT and GelSight (elastic deformation by a difference of
//!   Gaussians, internal shadow, coloured lights, final blur).
//! - [`geltip`]: the GelTip model (elastic deformation, back-projection, light fields).
//!
//! Images are row-major, top row first; colours RGB.

mod field;
pub mod filter;
pub mod geltip;
pub mod noise;
pub mod npy;
pub mod phong;

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
