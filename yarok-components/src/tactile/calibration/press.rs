//! [`Press`]: one real frame of a ball pressed into the gel, with where and how wide.

use image::RgbImage;

use super::CalibrationError;

/// A real frame of a ball pressed into the gel: the frame, and the centre (column, row, pixels
/// from the top-left corner) and radius (pixels) of its imprint — the contact circle where it
/// was measured, or the visible imprint, which [`FitSettings::contact_scales`] relate to the
/// contact circle.
///
/// [`FitSettings::contact_scales`]: super::FitSettings::contact_scales
#[derive(Debug, Clone)]
pub struct Press {
    /// The frame, RGB.
    pub frame: RgbImage,
    /// Centre of the imprint: column, row.
    pub centre: [f64; 2],
    /// Radius of the imprint, pixels.
    pub radius: f64,
}

/// How far (pixels) each pixel of a `width × height` gel sinks under a ball of `ball_radius`
/// pixels pressed at `centre` (column, row) until its contact circle is `contact_radius` wide:
/// a spherical cap, zero outside the circle. Row-major, top row first.
///
/// ```
/// use yarok_components::tactile::calibration::ball_press;
///
/// let heights = ball_press(9, 9, [4.5, 4.5], 3.0, 5.0);
/// assert_eq!(heights[0], 0.0);
/// assert!((heights[4 * 9 + 4] - 1.0).abs() < 1e-12); // 5 − √(5² − 3²)
/// ```
pub fn ball_press(
    width: usize,
    height: usize,
    centre: [f64; 2],
    contact_radius: f64,
    ball_radius: f64,
) -> Vec<f64> {
    let contact_radius = contact_radius.min(ball_radius);
    let deepest =
        ball_radius - (ball_radius * ball_radius - contact_radius * contact_radius).sqrt();
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let dx = x as f64 + 0.5 - centre[0];
            let dy = y as f64 + 0.5 - centre[1];
            let squared = dx * dx + dy * dy;
            if squared < contact_radius * contact_radius {
                (ball_radius * ball_radius - squared).sqrt() - (ball_radius - deepest)
            } else {
                0.0
            }
        })
        .collect()
}

/// Whether pixel (`x`, `y`) lies within `scale` radii of the press's centre.
pub(super) fn within(press: &Press, x: usize, y: usize, scale: f64) -> bool {
    let dx = x as f64 + 0.5 - press.centre[0];
    let dy = y as f64 + 0.5 - press.centre[1];
    dx * dx + dy * dy < (scale * press.radius).powi(2)
}

/// Reads a set of presses: a CSV file with a header and rows `frame, center_x, center_y,
/// radius_px` (the frame's name without `.png`, the imprint's centre column and row and its
/// radius in pixels), the frames being `frames/FRAME.png` beside it. Returns each press with
/// its frame's name.
///
/// # Errors
///
/// [`CalibrationError::Io`] if a file cannot be read, [`CalibrationError::Format`] naming the
/// file and line if a row or frame is not one.
pub fn read_presses(csv: &str) -> Result<Vec<(String, Press)>, CalibrationError> {
    let io = |path: &str| {
        let path = path.to_owned();
        move |source| CalibrationError::Io { path, source }
    };
    let text = std::fs::read_to_string(csv).map_err(io(csv))?;
    let folder = std::path::Path::new(csv)
        .parent()
        .unwrap_or(std::path::Path::new("."))
        .join("frames");
    let mut presses = Vec::new();
    for (number, line) in text.lines().enumerate().skip(1) {
        if line.trim().is_empty() {
            continue;
        }
        let format = |reason: String| CalibrationError::Format {
            path: format!("{csv}:{}", number + 1),
            reason,
        };
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let [name, x, y, radius] = fields[..] else {
            return Err(format(format!(
                "expected 4 fields (frame, center_x, center_y, radius_px), found {}",
                fields.len()
            )));
        };
        let number_of = |field: &str, what: &str| {
            field
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format(format!("{what} {field:?} is not a finite number")))
        };
        let (x, y, radius) = (
            number_of(x, "center_x")?,
            number_of(y, "center_y")?,
            number_of(radius, "radius_px")?,
        );
        if name.is_empty() || name.contains(['/', '\\']) || name.starts_with('.') {
            return Err(format(format!("frame {name:?} is not a file name")));
        }
        let path = folder.join(format!("{name}.png"));
        let shown = path.display().to_string();
        let frame = image::open(&path)
            .map_err(|e| format(format!("frame {shown}: {e}")))?
            .to_rgb8();
        presses.push((
            name.to_owned(),
            Press {
                frame,
                centre: [x, y],
                radius,
            },
        ));
    }
    Ok(presses)
}

/// Whether the frame named `name` is held out of calibration when every `every`-th is: its
/// number is one less than a multiple of `every` (with 3: `0002`, `0005`, …). Names that are not
/// numbers, and any name when `every` is 0, are not held out.
///
/// ```
/// use yarok_components::tactile::calibration::held_out;
///
/// assert!(held_out("0005", 3) && !held_out("0006", 3) && !held_out("0005", 0));
/// ```
pub fn held_out(name: &str, every: u32) -> bool {
    every > 0 && name.parse::<u32>().is_ok_and(|n| n % every == every - 1)
}

/// Splits named presses into those to calibrate with and those held out (see [`held_out`]),
/// each in the order given.
pub fn split_held_out(presses: Vec<(String, Press)>, every: u32) -> (Vec<Press>, Vec<Press>) {
    let (held, kept): (Vec<_>, Vec<_>) = presses
        .into_iter()
        .partition(|(name, _)| held_out(name, every));
    let presses = |named: Vec<(String, Press)>| named.into_iter().map(|(_, p)| p).collect();
    (presses(kept), presses(held))
}
