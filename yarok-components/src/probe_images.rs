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

/// A depth image as a probe shows it, written in counts of `unit` metres (see
/// [`ProbeImage::Depth`]).
pub(crate) fn depth(image: DepthImage, unit: f32) -> ProbeImage {
    let (width, height) = image.dimensions();
    ProbeImage::Depth {
        width,
        height,
        metres: image.into_raw(),
        unit,
    }
}

/// The PNG text keyword under which a depth PNG states its unit, in metres (`1e-6`: a count is
/// a micrometre).
pub const DEPTH_UNIT_KEYWORD: &str = "depth_unit_m";

/// `image` as PNG, as recorders and the bridge send it: colour as 8-bit RGB; depth as 16-bit
/// grey (big-endian, as the PNG standard has it) in counts of the image's unit, which a text
/// chunk [`DEPTH_UNIT_KEYWORD`] states (`1e-6`), 0 where there is no depth (nothing within
/// range, or not a number) and 65535 beyond the range.
///
/// # Errors
///
/// If the image cannot be encoded (its sizes do not match its data), or is of an unknown kind.
///
/// # Examples
///
/// ```
/// use yarok_components::probe_images::png;
/// use yarok_core::component::ProbeImage;
///
/// let depth = ProbeImage::Depth { width: 2, height: 1, metres: vec![0.018, 0.0163], unit: 1e-6 };
/// let bytes = png(&depth)?;
/// let decoded = image::load_from_memory(&bytes)?.to_luma16();
/// assert_eq!(decoded.into_raw(), [18000, 16300]);
/// # Ok::<(), yarok_core::BoxError>(())
/// ```
pub fn png(image: &ProbeImage) -> Result<Vec<u8>, yarok_core::BoxError> {
    let mut out = Vec::new();
    let (width, height) = image.size();
    let mut encoder = ::png::Encoder::new(&mut out, width, height);
    encoder.set_compression(::png::Compression::Fast);
    encoder.set_filter(::png::Filter::Sub);
    match image {
        ProbeImage::Rgb { pixels, .. } => {
            encoder.set_color(::png::ColorType::Rgb);
            encoder.set_depth(::png::BitDepth::Eight);
            encoder.write_header()?.write_image_data(pixels)?;
        }
        ProbeImage::Depth { metres, unit, .. } => {
            encoder.set_color(::png::ColorType::Grayscale);
            encoder.set_depth(::png::BitDepth::Sixteen);
            encoder.add_text_chunk(DEPTH_UNIT_KEYWORD.into(), format!("{unit:e}"))?;
            let bytes: Vec<u8> = metres
                .iter()
                .flat_map(|m| counts(*m, *unit).to_be_bytes())
                .collect();
            encoder.write_header()?.write_image_data(&bytes)?;
        }
        _ => return Err("a probe image of an unknown kind".into()),
    }
    Ok(out)
}

/// `metres` in counts of `unit`: 0 for no depth, 65535 beyond the range.
fn counts(metres: f32, unit: f32) -> u16 {
    if metres.is_nan() || metres <= 0.0 {
        return 0;
    }
    (f64::from(metres) / f64::from(unit))
        .round()
        .clamp(1.0, f64::from(u16::MAX)) as u16
}
