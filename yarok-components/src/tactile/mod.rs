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

mod field;
pub mod filter;
pub mod geltip;
pub mod light_fields;
pub mod noise;
pub mod npy;
pub mod phong;
mod rows;

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
