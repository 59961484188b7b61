//! Images as probes show them ([`ProbeImage`]).

use image::RgbImage;
use yarok_core::component::ProbeImage;
use yarok_mjc::DepthImage;

/// A colour image as a probe shows it.
pub(crate) fn rgb(image: RgbImage) -> ProbeImage {
    let (width, height) = image.dimensions();
    ProbeImage::Rgb {
        width,
        height,
        pixels: image.into_raw(),
    }
}

/// A depth image as a probe shows it.
pub(crate) fn depth(image: DepthImage) -> ProbeImage {
    let (width, height) = image.dimensions();
    ProbeImage::Depth {
        width,
        height,
        metres: image.into_raw(),
    }
}
