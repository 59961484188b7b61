//! A [`Calibration`] as a JSON file: its geometry, its coefficients named by their terms, and
//! the untouched gel as a base64 PNG.

use base64::Engine;
use image::{ImageEncoder, RgbImage};
use serde::{Deserialize, Serialize};

use yarok_core::OutputError;
use yarok_core::output::head;
use yarok_core::output_file::write_output;

use super::surface::{EVERYWHERE, NORMAL_TERMS, POSITION_TERMS};
use super::{Calibration, CalibrationError, Geometry, Placement};

/// The format's name and version, the file's first field.
const FORMAT: &str = "yarok tactile calibration 1";

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CalibrationFile {
    format: String,
    /// The sensor it is of; files before sensors were stated have none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sensor: Option<String>,
    width: u32,
    height: u32,
    pixels_per_mm: f64,
    ball_diameter_mm: f64,
    contact_scale: f64,
    spread_pixels: f64,
    /// Where presses appear from where they are described; files before it was fitted (and
    /// calibrations placing every press where it is described) have none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    placement: Option<PlacementFile>,
    normal_terms: Vec<String>,
    position_terms: Vec<String>,
    /// Per normal term, per position term: R, G, B.
    coefficients: Vec<[f64; 3]>,
    /// The camera's noise, standard deviation per channel (levels).
    noise_levels: [f64; 3],
    /// Where the calibration presses reached (`[x_min, y_min, x_max, y_max]`, from the image's
    /// centre in image widths and heights); files before it was stated extrapolate everywhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    covered: Option<[f64; 4]>,
    background_png: String,
}

/// A [`Placement`] in a calibration file.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PlacementFile {
    /// [`Placement::shift`], columns and rows.
    shift_pixels: [f64; 2],
    /// [`Placement::stretch`], columns and rows.
    stretch: [f64; 2],
}

impl Calibration {
    /// The calibration as the JSON a calibration file holds (deterministic).
    pub fn to_json(&self) -> String {
        let mut png = Vec::new();
        image::codecs::png::PngEncoder::new(&mut png)
            .write_image(
                self.background.as_raw(),
                self.background.width(),
                self.background.height(),
                image::ExtendedColorType::Rgb8,
            )
            .expect("an RGB image encodes as PNG");
        let file = CalibrationFile {
            format: FORMAT.to_owned(),
            sensor: self.sensor.clone(),
            width: self.background.width(),
            height: self.background.height(),
            pixels_per_mm: self.geometry.pixels_per_mm,
            ball_diameter_mm: self.geometry.ball_diameter_mm,
            contact_scale: self.geometry.contact_scale,
            spread_pixels: self.geometry.spread,
            placement: (!self.geometry.placement.is_identity()).then_some(PlacementFile {
                shift_pixels: self.geometry.placement.shift,
                stretch: self.geometry.placement.stretch,
            }),
            normal_terms: NORMAL_TERMS.map(str::to_owned).to_vec(),
            position_terms: POSITION_TERMS.map(str::to_owned).to_vec(),
            coefficients: self.coefficients.clone(),
            noise_levels: self.noise,
            covered: (self.covered != EVERYWHERE).then_some(self.covered),
            background_png: base64::engine::general_purpose::STANDARD.encode(png),
        };
        serde_json::to_string_pretty(&file).expect("a calibration serialises") + "\n"
    }

    /// Writes the calibration to `path` as JSON, replacing only a calibration file.
    ///
    /// # Errors
    ///
    /// [`CalibrationError::Refused`] when `path` holds a file that is not a calibration (it is
    /// left as it is); [`CalibrationError::Io`] naming the file.
    pub fn save(&self, path: &str) -> Result<(), CalibrationError> {
        let json = self.to_json();
        write_output(
            path.as_ref(),
            "calibration",
            calibration_file,
            json.as_bytes(),
        )
        .map_err(|refused| match refused {
            OutputError::Unwritable { source, .. } => CalibrationError::Io {
                path: path.to_owned(),
                source,
            },
            refused => CalibrationError::Refused(refused),
        })
    }

    /// Reads a calibration file written by [`Calibration::save`] (or `yarok tactile
    /// calibrate`).
    ///
    /// # Errors
    ///
    /// [`CalibrationError::Io`] if it cannot be read, [`CalibrationError::Format`] (naming the
    /// file and what is wrong) if it is not a calibration.
    pub fn load(path: &str) -> Result<Self, CalibrationError> {
        let limit = yarok_core::bounded::TEMPLATE_LIMIT;
        let text = yarok_core::bounded::read_text(path.as_ref(), limit).map_err(|source| {
            CalibrationError::Io {
                path: path.to_owned(),
                source,
            }
        })?;
        parse(&text, path)
    }
}

/// Whether the file at `path` is a calibration file: a JSON object whose first field names
/// the format.
fn calibration_file(path: &std::path::Path) -> std::io::Result<bool> {
    let head = head(path, 256)?;
    let text = String::from_utf8_lossy(&head);
    let first_field = text.trim_start().strip_prefix('{').map(str::trim_start);
    Ok(first_field.is_some_and(|field| {
        field
            .strip_prefix("\"format\"")
            .map(str::trim_start)
            .and_then(|rest| rest.strip_prefix(':'))
            .is_some_and(|rest| {
                let format = FORMAT.rsplit_once(' ').map_or(FORMAT, |(name, _)| name);
                rest.trim_start().starts_with(&format!("\"{format}"))
            })
    }))
}

/// The calibration in `text`, read from `path` (for errors).
pub(super) fn parse(text: &str, path: &str) -> Result<Calibration, CalibrationError> {
    let format = |reason: String| CalibrationError::Format {
        path: path.to_owned(),
        reason,
    };
    let file: CalibrationFile = serde_json::from_str(text).map_err(|e| {
        format(format!(
            "not a calibration (line {}, column {}): {e}",
            e.line(),
            e.column()
        ))
    })?;
    if file.format != FORMAT {
        return Err(format(format!(
            "format {:?}, expected {FORMAT:?}",
            file.format
        )));
    }
    if file.normal_terms != NORMAL_TERMS || file.position_terms != POSITION_TERMS {
        return Err(format(format!(
            "its terms ({:?} × {:?}) are not this version's ({NORMAL_TERMS:?} × {POSITION_TERMS:?})",
            file.normal_terms, file.position_terms
        )));
    }
    let png = base64::engine::general_purpose::STANDARD
        .decode(&file.background_png)
        .map_err(|e| format(format!("background_png is not base64: {e}")))?;
    let background: RgbImage = image::load_from_memory_with_format(&png, image::ImageFormat::Png)
        .map_err(|e| format(format!("background_png is not a PNG: {e}")))?
        .to_rgb8();
    if background.dimensions() != (file.width, file.height) {
        return Err(format(format!(
            "the background is {}×{}, the file says {}×{}",
            background.width(),
            background.height(),
            file.width,
            file.height
        )));
    }
    let geometry = Geometry {
        pixels_per_mm: file.pixels_per_mm,
        ball_diameter_mm: file.ball_diameter_mm,
        contact_scale: file.contact_scale,
        spread: file.spread_pixels,
        placement: file
            .placement
            .map_or_else(Placement::default, |p| Placement {
                shift: p.shift_pixels,
                stretch: p.stretch,
            }),
    };
    for (name, value) in [
        ("pixels_per_mm", geometry.pixels_per_mm),
        ("ball_diameter_mm", geometry.ball_diameter_mm),
        ("contact_scale", geometry.contact_scale),
        ("spread_pixels", geometry.spread),
    ] {
        super::fit::check_setting(name, value).map_err(|refused| format(refused.to_string()))?;
    }
    geometry
        .placement
        .check()
        .map_err(|beyond| format(beyond.to_string()))?;
    let covered = file.covered.unwrap_or(EVERYWHERE);
    let calibration = Calibration::new(
        background,
        geometry,
        file.coefficients,
        file.noise_levels,
        covered,
    )
    .map_err(|e| format(e.to_string()))?;
    match file.sensor {
        Some(sensor) => calibration
            .for_sensor(&sensor)
            .map_err(|e| format(e.to_string())),
        None => Ok(calibration),
    }
}
