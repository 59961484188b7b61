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
/// pixels pressed at `centre` (column, row) until its contact circle is `contact_radius` wide
/// (at most the ball's), by Hertz's law of a ball pressed into an elastic half-space: the ball
/// sinks `a²/R` (`a` the contact radius, `R` the ball's); within the contact the gel follows the
/// ball, `a²/R − r²/(2R)`; outside it the gel is drawn down with the ball,
/// `a²/(πR) · ((2 − r²/a²)·asin(a/r) + √(r²/a² − 1))`, meeting it at the circle. Row-major, top
/// row first.
///
/// ```
/// use yarok_components::tactile::calibration::ball_press;
///
/// let heights = ball_press(9, 9, [4.5, 4.5], 3.0, 5.0);
/// assert!((heights[4 * 9 + 4] - 1.8).abs() < 1e-12); // 3²/5 at the centre
/// assert!(heights[0] > 0.0 && heights[0] < 0.9); // drawn down outside the contact, less
/// ```
pub fn ball_press(
    width: usize,
    height: usize,
    centre: [f64; 2],
    contact_radius: f64,
    ball_radius: f64,
) -> Vec<f64> {
    let a = contact_radius.min(ball_radius);
    let depth = a * a / ball_radius;
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let dx = x as f64 + 0.5 - centre[0];
            let dy = y as f64 + 0.5 - centre[1];
            let squared = dx * dx + dy * dy;
            if squared < a * a {
                depth - squared / (2.0 * ball_radius)
            } else if a > 0.0 {
                let ratio = squared / (a * a);
                depth / std::f64::consts::PI
                    * ((2.0 - ratio) * (1.0 / ratio.sqrt()).asin() + (ratio - 1.0).sqrt())
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

/// The columns a press list names in its header, in any order (others are ignored).
const COLUMNS: [&str; 4] = ["frame", "center_x", "center_y", "radius_px"];

/// Reads a set of presses: a CSV file whose header names the columns `frame`, `center_x`,
/// `center_y` and `radius_px` (in any order; others are ignored) — the frame's name without
/// `.png`, the imprint's centre column and row and its radius in pixels — the frames being
/// `frames/FRAME.png` beside it. Returns each press with its frame's name.
///
/// # Errors
///
/// [`CalibrationError::Io`] if a file cannot be read, [`CalibrationError::Format`] naming the
/// file and line if the header does not name the columns, a row or frame is not one, a frame is
/// named twice, a centre is off its frame or a radius is not between a pixel and half the
/// frame's larger side, or the frames are not all of one size and kind (all colour, or all
/// grey).
pub fn read_presses(csv: &str) -> Result<Vec<(String, Press)>, CalibrationError> {
    let io = |path: &str| {
        let path = path.to_owned();
        move |source| CalibrationError::Io { path, source }
    };
    let text = yarok_core::bounded::read_text(csv.as_ref(), yarok_core::bounded::TEMPLATE_LIMIT)
        .map_err(io(csv))?;
    let folder = std::path::Path::new(csv)
        .parent()
        .unwrap_or(std::path::Path::new("."))
        .join("frames");
    let format = |number: usize, reason: String| CalibrationError::Format {
        path: format!("{csv}:{}", number + 1),
        reason,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, line)| !line.trim().is_empty());
    let (header_number, header) = lines
        .next()
        .ok_or_else(|| format(0, "no header and no presses".to_owned()))?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let column = |wanted: &str| names.iter().position(|name| *name == wanted);
    let [frame_at, x_at, y_at, radius_at] = COLUMNS.map(column);
    let (Some(frame_at), Some(x_at), Some(y_at), Some(radius_at)) =
        (frame_at, x_at, y_at, radius_at)
    else {
        return Err(format(
            header_number,
            format!(
                "the header must name the columns {} (in any order); it is {header:?}{}",
                COLUMNS.join(", "),
                if names.iter().any(|name| name.parse::<f64>().is_ok()) {
                    " (a row of numbers: a file without a header would lose its first press)"
                } else {
                    ""
                }
            ),
        ));
    };
    let mut presses: Vec<(String, Press)> = Vec::new();
    let mut first_lines: Vec<usize> = Vec::new();
    let mut kind = None;
    for (number, line) in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != names.len() {
            return Err(format(
                number,
                format!(
                    "{} fields where the header names {}",
                    fields.len(),
                    names.len()
                ),
            ));
        }
        let name = fields[frame_at];
        let number_of = |at: usize| {
            fields[at]
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    format(
                        number,
                        format!("{} {:?} is not a finite number", names[at], fields[at]),
                    )
                })
        };
        let (x, y, radius) = (number_of(x_at)?, number_of(y_at)?, number_of(radius_at)?);
        if name.is_empty() || name.contains(['/', '\\']) || name.starts_with('.') {
            return Err(format(number, format!("frame {name:?} is not a file name")));
        }
        if let Some(earlier) = presses.iter().position(|(earlier, _)| earlier == name) {
            return Err(format(
                number,
                format!(
                    "frame {name:?} is on line {} already: each frame is one press",
                    first_lines[earlier] + 1
                ),
            ));
        }
        let path = folder.join(format!("{name}.png"));
        let shown = path.display().to_string();
        let image =
            image::open(&path).map_err(|e| format(number, format!("frame {shown}: {e}")))?;
        let this_kind = (image.width(), image.height(), image.color().has_color());
        let (width, height, colour) = *kind.get_or_insert(this_kind);
        if this_kind != (width, height, colour) {
            let describe = |(w, h, colour): (u32, u32, bool)| {
                format!("{w}×{h} {}", if colour { "colour" } else { "grey" })
            };
            return Err(format(
                number,
                format!(
                    "frame {shown} is {} where the first frame is {}: the frames of a press \
                     list come from one sensor",
                    describe(this_kind),
                    describe((width, height, colour))
                ),
            ));
        }
        let (w, h) = (f64::from(width), f64::from(height));
        if !((0.0..=w).contains(&x) && (0.0..=h).contains(&y)) {
            return Err(format(
                number,
                format!("centre ({x}, {y}) is off its {width}×{height} frame"),
            ));
        }
        let largest = w.max(h) / 2.0;
        if !(1.0..=largest).contains(&radius) {
            return Err(format(
                number,
                format!("radius_px {radius} is not between 1 and {largest} (half the frame)"),
            ));
        }
        first_lines.push(number);
        presses.push((
            name.to_owned(),
            Press {
                frame: image.to_rgb8(),
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
