//! Depth images: what a camera's depth rendering (feature `render`) and a mock camera give.

use image::{ImageBuffer, Luma};

/// A depth image: planar distance from the camera, in metres, top row first.
pub type DepthImage = ImageBuffer<Luma<f32>, Vec<f32>>;

/// Converts a depth image to 16-bit millimetres (rounded, saturating at 65.535 m), the usual
/// format of depth PNGs.
///
/// # Examples
///
/// ```
/// use yarok_mjc::{DepthImage, depth_to_millimetres};
///
/// let depth = DepthImage::from_pixel(2, 1, image::Luma([0.2504]));
/// assert_eq!(depth_to_millimetres(&depth).get_pixel(0, 0)[0], 250);
/// ```
pub fn depth_to_millimetres(depth: &DepthImage) -> ImageBuffer<Luma<u16>, Vec<u16>> {
    ImageBuffer::from_fn(depth.width(), depth.height(), |x, y| {
        let mm = (f64::from(depth.get_pixel(x, y)[0]) * 1000.0).round();
        Luma([mm.clamp(0.0, f64::from(u16::MAX)) as u16])
    })
}
