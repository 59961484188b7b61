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

/// What a PNG yarok writes says under the standard `Software` keyword (with yarok's version):
/// how an existing image is known as yarok's.
const SOFTWARE: &str = "yarok";

/// `image` as PNG, as the Zenoh bridge sends it (and recorders colour images): colour as 8-bit
/// RGB; depth as 16-bit grey (big-endian, as the PNG standard has it) in counts of the image's
/// unit, which a text chunk [`DEPTH_UNIT_KEYWORD`] states (`1e-6`), 0 where there is no depth
/// (nothing within range, or not a number) and 65535 beyond the range. The `Software` text
/// names yarok.
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
    encoder.add_text_chunk(
        "Software".into(),
        format!("{SOFTWARE} {}", env!("CARGO_PKG_VERSION")),
    )?;
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

/// Writes `image` to `path` as a PNG ([`png()`]), making its folder, and replacing only a PNG
/// yarok wrote (a user's file there is refused and kept).
///
/// # Errors
///
/// When a file yarok did not write is at `path`, or the image cannot be encoded or written,
/// naming the path.
pub fn save_png(
    image: RgbImage,
    path: impl AsRef<std::path::Path>,
) -> Result<(), yarok_core::BoxError> {
    let path = path.as_ref();
    let bytes = png(&rgb(image)).map_err(|e| format!("{}: {e}", path.display()))?;
    yarok_core::output_file::write_output(path, "PNG image", png_by_yarok, &bytes)?;
    Ok(())
}

/// Whether the file at `path` is a PNG yarok wrote with [`png()`]: its `Software` text names
/// yarok.
///
/// # Errors
///
/// When the file cannot be read.
pub fn png_by_yarok(path: &std::path::Path) -> std::io::Result<bool> {
    let file = std::io::BufReader::new(std::fs::File::open(path)?);
    let Ok(reader) = ::png::Decoder::new(file).read_info() else {
        return Ok(false);
    };
    Ok(reader.info().uncompressed_latin1_text.iter().any(|text| {
        text.keyword == "Software"
            && (text.text == SOFTWARE || text.text.starts_with(&format!("{SOFTWARE} ")))
    }))
}

/// `metres` in counts of `unit`: 0 for no depth, 65535 beyond the range.
pub(crate) fn counts(metres: f32, unit: f32) -> u16 {
    if metres.is_nan() || metres <= 0.0 {
        return 0;
    }
    (f64::from(metres) / f64::from(unit))
        .round()
        .clamp(1.0, f64::from(u16::MAX)) as u16
}

/// Reads a depth PNG as [`png()`] writes it (or any 16-bit grey PNG): columns, rows and the depth
/// in metres, row-major, `NaN` where a pixel holds 0 (no depth). The unit is the PNG's
/// [`DEPTH_UNIT_KEYWORD`] text, or millimetres without one (the usual depth PNG).
///
/// ```
/// use yarok_components::probe_images::{depth_from_png, png};
/// use yarok_core::component::ProbeImage;
///
/// let depth = ProbeImage::Depth { width: 2, height: 1, metres: vec![0.018, 0.0], unit: 1e-6 };
/// let (width, height, metres) = depth_from_png(&png(&depth)?)?;
/// assert_eq!((width, height, metres[0]), (2, 1, 0.018));
/// assert!(metres[1].is_nan());
/// # Ok::<(), yarok_core::BoxError>(())
/// ```
///
/// # Errors
///
/// A message saying what is wrong: not a PNG, not 16-bit grey (an 8-bit or colour image holds
/// no metric depth), an unreadable or non-positive unit, or a size over 16384 × 16384.
pub fn depth_from_png(bytes: &[u8]) -> Result<(u32, u32, Vec<f32>), String> {
    let mut decoder = ::png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(::png::Transformations::IDENTITY);
    let mut reader = decoder.read_info().map_err(|e| format!("not a PNG: {e}"))?;
    let info = reader.info();
    let (width, height) = (info.width, info.height);
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(format!(
            "{width} × {height} is larger than {MAX_SIDE} × {MAX_SIDE}"
        ));
    }
    if (info.color_type, info.bit_depth) != (::png::ColorType::Grayscale, ::png::BitDepth::Sixteen)
    {
        return Err(format!(
            "a {:?}-bit {:?} PNG holds no metric depth: a depth PNG is 16-bit grey",
            info.bit_depth as u8, info.color_type
        ));
    }
    let unit = info
        .uncompressed_latin1_text
        .iter()
        .find(|text| text.keyword == DEPTH_UNIT_KEYWORD)
        .map(|text| text.text.clone())
        .or_else(|| {
            info.utf8_text
                .iter()
                .find(|text| text.keyword == DEPTH_UNIT_KEYWORD)
                .and_then(|text| text.get_text().ok())
        });
    let unit: f64 = match unit {
        None => 1e-3,
        Some(text) => text
            .trim()
            .parse()
            .ok()
            .filter(|unit: &f64| unit.is_finite() && *unit > 0.0)
            .ok_or_else(|| format!("its {DEPTH_UNIT_KEYWORD} {text:?} is not a positive number"))?,
    };
    let mut buffer = vec![
        0;
        reader
            .output_buffer_size()
            .ok_or("the image is too large")?
    ];
    let frame = reader
        .next_frame(&mut buffer)
        .map_err(|e| format!("its pixels cannot be read: {e}"))?;
    let metres = buffer[..frame.buffer_size()]
        .chunks_exact(2)
        .map(|pair| match u16::from_be_bytes([pair[0], pair[1]]) {
            0 => f32::NAN,
            count => (f64::from(count) * unit) as f32,
        })
        .collect();
    Ok((width, height, metres))
}

/// The largest side a depth PNG may have (as MuJoCo's offscreen buffers).
const MAX_SIDE: u32 = 16384;
