//! Frames as cameras deliver them — MJPEG or YUYV (YUV 4:2:2) — decoded into RGB images, the
//! type `sim` cameras give.

use image::RgbImage;

/// How a camera encodes its frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum PixelFormat {
    /// Each frame a JPEG image (USB cameras' compressed mode; DIGIT's 640×480 at 30 fps).
    Mjpeg,
    /// YUV 4:2:2 interleaved `Y0 U Y1 V`, two bytes a pixel, BT.601 limited range.
    Yuyv,
}

/// A frame could not be decoded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DecodeError {
    /// The JPEG data is not a decodable image.
    #[error("a {width}x{height} MJPEG frame of {bytes} bytes does not decode: {reason}")]
    Jpeg {
        /// Expected width.
        width: u32,
        /// Expected height.
        height: u32,
        /// The frame's size.
        bytes: usize,
        /// The decoder's words.
        reason: String,
    },
    /// The frame is not the size the camera was set to.
    #[error("a {format:?} frame of {got} is not {width}x{height}")]
    Size {
        /// The format.
        format: PixelFormat,
        /// What came (bytes for YUYV, pixels `WxH` for MJPEG).
        got: String,
        /// Expected width.
        width: u32,
        /// Expected height.
        height: u32,
    },
}

/// Decodes one frame of `format`, which must be `width` × `height` pixels.
///
/// # Errors
///
/// [`DecodeError`] for data that does not decode or is not that size.
///
/// ```
/// use yarok_hw::camera::{PixelFormat, decode};
///
/// // Two pixels of YUYV: white, then black, sharing a neutral chroma.
/// let rgb = decode(PixelFormat::Yuyv, 2, 1, &[235, 128, 16, 128])?;
/// assert_eq!(rgb.as_raw(), &[255, 255, 255, 0, 0, 0]);
/// # Ok::<(), yarok_hw::camera::DecodeError>(())
/// ```
pub fn decode(
    format: PixelFormat,
    width: u32,
    height: u32,
    bytes: &[u8],
) -> Result<RgbImage, DecodeError> {
    match format {
        PixelFormat::Mjpeg => decode_jpeg(width, height, bytes),
        PixelFormat::Yuyv => decode_yuyv(width, height, bytes),
    }
}

fn decode_jpeg(width: u32, height: u32, bytes: &[u8]) -> Result<RgbImage, DecodeError> {
    let image = image::load_from_memory_with_format(bytes, image::ImageFormat::Jpeg)
        .map_err(|error| DecodeError::Jpeg {
            width,
            height,
            bytes: bytes.len(),
            reason: error.to_string(),
        })?
        .into_rgb8();
    if image.dimensions() != (width, height) {
        return Err(DecodeError::Size {
            format: PixelFormat::Mjpeg,
            got: format!("{}x{} pixels", image.width(), image.height()),
            width,
            height,
        });
    }
    Ok(image)
}

fn decode_yuyv(width: u32, height: u32, bytes: &[u8]) -> Result<RgbImage, DecodeError> {
    let pixels = width as usize * height as usize;
    if !width.is_multiple_of(2) || bytes.len() != 2 * pixels {
        return Err(DecodeError::Size {
            format: PixelFormat::Yuyv,
            got: format!("{} bytes", bytes.len()),
            width,
            height,
        });
    }
    let mut rgb = Vec::with_capacity(3 * pixels);
    for pair in bytes.chunks_exact(4) {
        let [y0, u, y1, v] = [pair[0], pair[1], pair[2], pair[3]].map(i32::from);
        for y in [y0, y1] {
            rgb.extend(bt601(y, u, v));
        }
    }
    Ok(RgbImage::from_raw(width, height, rgb).expect("three bytes a pixel"))
}

/// One pixel of BT.601 limited-range YUV as RGB, in 8.8 fixed point.
fn bt601(y: i32, u: i32, v: i32) -> [u8; 3] {
    let (c, d, e) = (298 * (y - 16), u - 128, v - 128);
    let channel = |value: i32| ((value + 128) >> 8).clamp(0, 255) as u8;
    [
        channel(c + 409 * e),
        channel(c - 100 * d - 208 * e),
        channel(c + 516 * d),
    ]
}
