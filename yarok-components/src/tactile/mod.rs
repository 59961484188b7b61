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
