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

/// `image` as PNG: colour as 8-bit RGB, depth as 16-bit grey millimetres.
pub(crate) fn png(image: &ProbeImage) -> Result<Vec<u8>, yarok_core::BoxError> {
    use image::ImageEncoder;
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};

    let mut out = Vec::new();
    let encoder = PngEncoder::new_with_quality(&mut out, CompressionType::Fast, FilterType::Sub);
    match image {
        ProbeImage::Rgb {
            width,
            height,
            pixels,
        } => encoder.write_image(pixels, *width, *height, image::ExtendedColorType::Rgb8)?,
        ProbeImage::Depth {
            width,
            height,
            metres,
        } => {
            let bytes: Vec<u8> = metres
                .iter()
                .flat_map(|m| ((m * 1000.0).round().clamp(0.0, 65535.0) as u16).to_be_bytes())
                .collect();
            encoder.write_image(&bytes, *width, *height, image::ExtendedColorType::L16)?;
        }
        _ => return Err("a probe image of an unknown kind".into()),
    }
    Ok(out)
}
