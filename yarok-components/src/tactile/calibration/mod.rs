//! A tactile sensor's optical model calibrated from real frames: how the gel's surface (its
//! normal, its height and where on the gel it is) becomes colour, fitted to a few dozen frames
//! of a ball pressed into a real sensor, as Taxim, FOTS and digit-depth calibrate theirs.
//!
//! The model: the indentation map (pixels) is spread as the gel around a contact sinks with it
//! (a Gaussian of [`Geometry::spread`] pixels); each pixel's colour is the untouched gel's
//! (estimated from the frames) plus, per channel, a polynomial of the surface's normal and height
//! (third degree, [`NORMAL_TERMS`]) whose coefficients are polynomials of the pixel's position
//! (second degree, [`POSITION_TERMS`]: each light reaches each part of the gel at its own
//! angle). The coefficients are a least-squares fit to the presses, each press's indentation
//! being the ball's by Hertz's law ([`ball_press`]); the contact circle's scale (among those
//! that keep every press's contact circle within the ball) and the spread are chosen among
//! candidates by how well they fit; then where each press appears on the image (its
//! [`Placement`]: an offset, and a stretch from the gel's middle) is fitted to where each frame
//! shows its press best, and the colour model refitted there. The camera's noise is
//! measured too ([`Calibration::noise_levels`]); images are rendered without it (the expected
//! image), and a sensor in the world adds a fixed pattern of it when its `noise` is on.
//!
//! A calibration is saved as JSON (`yarok tactile calibrate` writes one; the DIGIT's bundled one,
//! [`Calibration::digit`], is fitted to a real DIGIT's frames from FOTS).
//!
//! ```
//! use yarok_components::tactile::calibration::Calibration;
//!
//! let digit = Calibration::digit();
//! let (width, height) = digit.size();
//! let untouched = digit.render_indentation(&vec![0.0; width * height], 5e-5)?;
//! assert_eq!(untouched, *digit.background());
//! let pressed = digit.render_press([120.0, 160.0], 40.0);
//! assert_ne!(pressed, untouched);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod coverage;
mod file;
mod fit;
mod fit_error;
mod placement;
mod press;
mod surface;

use std::sync::Arc;

use image::RgbImage;

pub use coverage::Coverage;
pub use fit::{FitSettings, SETTING_RANGES, check_setting};
pub use fit_error::{FitError, SettingError};
pub use placement::{PLACEMENT_LIMITS, Placement, PlacementOutOfRange};
pub use press::{Press, ball_press, held_out, read_presses, split_held_out};
pub use surface::{Area, NORMAL_TERMS, POSITION_TERMS};

use super::SizeError;

/// A calibration could not be fitted, read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CalibrationError {
    /// The presses or settings cannot be fitted.
    #[error("cannot calibrate: {0}")]
    Fit(#[from] FitError),
    /// A calibration file could not be read or written.
    #[error("calibration file {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// The path to write a calibration to cannot take it: a file yarok did not write is there
    /// (it is left as it is), or the folder for it cannot be made.
    #[error("{0}")]
    Refused(#[from] yarok_core::OutputError),
    /// A calibration file is not one.
    #[error("calibration file {path}: {reason}")]
    Format {
        /// The file.
        path: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// The press geometry a calibration was fitted with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// The frames' scale at the gel, pixels per millimetre.
    pub pixels_per_mm: f64,
    /// The pressing ball's diameter, millimetres.
    pub ball_diameter_mm: f64,
    /// The contact circle's radius as a multiple of a press's radius.
    pub contact_scale: f64,
    /// How far (Gaussian σ, pixels) the gel around a contact sinks with it.
    pub spread: f64,
    /// Where on the image a press appears, from where it is described.
    pub placement: Placement,
}

impl Geometry {
    /// How far (pixels) each pixel of a `width × height` gel sinks under this geometry's ball
    /// pressed at `centre` (column, row) with a press radius of `radius` pixels, before the
    /// spread: [`ball_press`] with the contact circle `contact_scale · radius`.
    pub fn press(&self, width: usize, height: usize, centre: [f64; 2], radius: f64) -> Vec<f64> {
        let ball_radius = self.ball_diameter_mm * self.pixels_per_mm / 2.0;
        ball_press(
            width,
            height,
            centre,
            self.contact_scale * radius,
            ball_radius,
        )
    }

    /// How deep (millimetres) a press of `radius` pixels sinks the ball under this geometry, by
    /// [`ball_press`]'s law (`a²/R` for a contact circle `a` = `contact_scale · radius` on a ball
    /// of radius `R`), and whether that circle was wider than the ball, so that the press is
    /// taken as the ball sunk to its equator.
    ///
    /// ```
    /// use yarok_components::tactile::calibration::Geometry;
    ///
    /// use yarok_components::tactile::calibration::Placement;
    ///
    /// let geometry = Geometry {
    ///     pixels_per_mm: 10.0,
    ///     ball_diameter_mm: 4.0,
    ///     contact_scale: 1.0,
    ///     spread: 0.0,
    ///     placement: Placement::default(),
    /// };
    /// let (depth, clamped) = geometry.depth_mm(12.0); // a 1.2 mm contact circle on a 2 mm ball
    /// assert!((depth - 0.72).abs() < 1e-12 && !clamped);
    /// assert_eq!(geometry.depth_mm(30.0), (2.0, true));
    /// ```
    pub fn depth_mm(&self, radius: f64) -> (f64, bool) {
        let ball = self.ball_diameter_mm / 2.0;
        let contact = self.contact_scale * radius / self.pixels_per_mm;
        let clamped = contact > ball;
        let contact = contact.min(ball);
        (contact * contact / ball, clamped)
    }

    /// [`Geometry::press`] on the half-resolution grid, spread and placed.
    fn heights(&self, width: usize, height: usize, centre: [f64; 2], radius: f64) -> Vec<f64> {
        let mut half = surface::halve(&self.press(width, height, centre, radius), width);
        self.spread_and_place(&mut half, (width, height), &mut Vec::new(), &mut Vec::new());
        half
    }

    /// Spreads a halved indentation map (pixels) of a `width × height` image and moves it to
    /// where its presses appear, with `scratch` and `placed` (their memory reused).
    fn spread_and_place(
        &self,
        half: &mut Vec<f64>,
        (width, height): (usize, usize),
        scratch: &mut Vec<f64>,
        placed: &mut Vec<f64>,
    ) {
        let half_width = width.div_ceil(surface::HALF);
        surface::spread_with(
            half,
            half_width,
            self.spread / surface::HALF as f64,
            scratch,
        );
        if !self.placement.is_identity() {
            self.placement
                .place_half(half, half_width, (width, height), placed);
            std::mem::swap(half, placed);
        }
    }
}

/// Buffers a [`Calibration`] renders frames with: once a frame of a size is rendered, the next
/// allocate nothing ([`Calibration::render_indentation_into`]).
#[derive(Debug, Default)]
pub struct RenderBuffers {
    /// The half-resolution spread indentation (pixels).
    heights: Vec<f64>,
    /// The spread's intermediate rows.
    scratch: Vec<f64>,
    /// The spread indentation moved to where its presses appear.
    placed: Vec<f64>,
    /// Per half-resolution point, its colour change (zero where the gel is untouched).
    changes: Vec<[f32; 3]>,
    /// Per column of the image, where it falls on the half-resolution grid.
    columns: Vec<(usize, usize, f64)>,
}

/// A calibrated optical model (see the [module](self)): cheap to clone (the per-pixel weights
/// are shared).
#[derive(Debug, Clone)]
pub struct Calibration {
    /// The sensor it is of (`digit`, `gelsight`, a user's name), when its file states one.
    sensor: Option<String>,
    background: RgbImage,
    geometry: Geometry,
    coefficients: Vec<[f64; 3]>,
    /// The camera's noise, per channel: standard deviation, levels.
    noise: [f64; 3],
    /// Where the calibration presses reached: beyond it, the colour polynomial's weights are
    /// those of the nearest point within it.
    covered: Area,
    /// Per point of the half-resolution grid, per channel (R, G, B), per normal term: the
    /// coefficients' position polynomials evaluated.
    weights: Arc<Vec<f32>>,
}

impl Calibration {
    fn new(
        background: RgbImage,
        geometry: Geometry,
        coefficients: Vec<[f64; 3]>,
        noise: [f64; 3],
        covered: Area,
    ) -> Result<Self, CalibrationError> {
        if covered[0] > covered[2] || covered[1] > covered[3] || covered.iter().any(|c| c.is_nan())
        {
            return Err(FitError::NotARectangle(covered).into());
        }
        if noise.iter().any(|n| !(n.is_finite() && *n >= 0.0)) {
            return Err(FitError::Noise(noise).into());
        }
        let terms = NORMAL_TERMS.len() * POSITION_TERMS.len();
        if coefficients.len() != terms || coefficients.iter().flatten().any(|c| !c.is_finite()) {
            return Err(FitError::Coefficients {
                needed: terms,
                given: coefficients.len(),
            }
            .into());
        }
        let (width, height) = (background.width() as usize, background.height() as usize);
        let (half_width, half_height) = surface::half_size(width, height);
        let mut weights = Vec::with_capacity(half_width * half_height * NORMAL_TERMS.len() * 3);
        for hy in 0..half_height {
            for hx in 0..half_width {
                let positions = surface::half_position_terms(hx, hy, width, height, &covered);
                for channel in 0..3 {
                    for term in coefficients.chunks_exact(POSITION_TERMS.len()) {
                        let weight: f64 = positions
                            .iter()
                            .zip(term)
                            .map(|(p, c)| p * c[channel])
                            .sum();
                        weights.push(weight as f32);
                    }
                }
            }
        }
        Ok(Self {
            sensor: None,
            background,
            geometry,
            coefficients,
            noise,
            covered,
            weights: Arc::new(weights),
        })
    }

    /// The calibration stating that it is of the sensor `sensor` (`digit`, `gelsight`, or a
    /// sensor of your own: letters, digits, `_` and `-`), as its file then says and as what
    /// loads it checks.
    ///
    /// # Errors
    ///
    /// [`CalibrationError::Fit`] when `sensor` is not such a name.
    pub fn for_sensor(mut self, sensor: &str) -> Result<Self, CalibrationError> {
        check_sensor_name(sensor).map_err(CalibrationError::Fit)?;
        self.sensor = Some(sensor.to_owned());
        Ok(self)
    }

    /// The sensor the calibration states it is of, if it states one.
    pub fn sensor(&self) -> Option<&str> {
        self.sensor.as_deref()
    }

    /// Checks that the calibration is of the sensor `kind` (a calibration that states no
    /// sensor is taken to be of any).
    ///
    /// # Errors
    ///
    /// A message naming both sensors.
    pub fn check_sensor(&self, kind: &str) -> Result<(), String> {
        match self.sensor() {
            Some(sensor) if sensor != kind => Err(format!(
                "a calibration of a {sensor} sensor, not of a {kind}: calibrate the {kind} \
                 (yarok tactile calibrate … --sensor {kind})"
            )),
            _ => Ok(()),
        }
    }

    /// Fits a calibration to a sensor's `untouched` frame and frames of a ball pressed into it
    /// (a few dozen, spread over the gel): the untouched gel is estimated from all of them, the
    /// colour polynomial fitted by least squares, and of `settings`' candidate geometries the
    /// one whose images of the presses are nearest the frames (mean absolute error within 1.5
    /// radii) kept. Deterministic: the same inputs give the same calibration, bit for bit.
    ///
    /// # Errors
    ///
    /// [`CalibrationError::Fit`] if there are no presses, a frame's size differs from the
    /// untouched frame's, a press is not finite and positive, a setting is outside its range
    /// ([`SETTING_RANGES`]), or the presses do not determine the model.
    pub fn fit(
        untouched: &RgbImage,
        presses: &[Press],
        settings: &FitSettings,
    ) -> Result<Self, CalibrationError> {
        fit::fit(untouched, presses, settings)
    }

    /// How far (columns, rows) its image of `press` must move from the press's described centre
    /// to match the press's frame best: the least mean absolute error within 1.5 radii of the
    /// described centre, to half a pixel. Fitting the [`Placement`] explains these moves of the
    /// calibration presses; what is left shows how well it does.
    pub fn best_move(&self, press: &Press) -> [f64; 2] {
        fit::best_move(self, press)
    }

    /// The calibration bundled for the DIGIT: fitted (contact scale 0.7, spread 6 pixels, as
    /// its file says) to the 14 calibration presses of a real DIGIT's frames from FOTS (MIT
    /// licence; see `yarok-components/data/tactile-real/`), the other 7 held out to measure it.
    pub fn digit() -> Self {
        file::parse(include_str!("digit.json"), "the bundled DIGIT calibration")
            .expect("the bundled calibration is valid (tested)")
    }

    /// Columns and rows of the images it renders.
    pub fn size(&self) -> (usize, usize) {
        (
            self.background.width() as usize,
            self.background.height() as usize,
        )
    }

    /// The untouched gel's image.
    pub fn background(&self) -> &RgbImage {
        &self.background
    }

    /// The camera noise of the frames it was fitted to: per channel (R, G, B), the standard
    /// deviation (levels) of a frame from the untouched gel where nothing presses.
    pub fn noise_levels(&self) -> [f64; 3] {
        self.noise
    }

    /// The geometry it was fitted with.
    pub fn geometry(&self) -> Geometry {
        self.geometry
    }

    /// The image of a gel sunk by `indentation` (metres per pixel, row-major, the image's size;
    /// zero where nothing presses), seen at `metres_per_pixel` at the gel.
    ///
    /// # Errors
    ///
    /// [`SizeError`] if `indentation` is not the image's size.
    pub fn render_indentation(
        &self,
        indentation: &[f32],
        metres_per_pixel: f64,
    ) -> Result<RgbImage, SizeError> {
        // Filled with the untouched gel by `render_indentation_into`.
        let mut image = RgbImage::new(self.background.width(), self.background.height());
        self.render_indentation_into(
            indentation,
            metres_per_pixel,
            &mut RenderBuffers::default(),
            &mut image,
        )?;
        Ok(image)
    }

    /// [`Calibration::render_indentation`] into `out` (RGB, the image's size), with `buffers`
    /// kept from frame to frame: once they have rendered a frame of this size, this allocates
    /// nothing.
    ///
    /// # Errors
    ///
    /// [`SizeError`] if `indentation` or `out` is not the image's size.
    pub fn render_indentation_into(
        &self,
        indentation: &[f32],
        metres_per_pixel: f64,
        buffers: &mut RenderBuffers,
        out: &mut [u8],
    ) -> Result<(), SizeError> {
        let (width, height) = self.size();
        super::expect_len("indentation map", indentation.len(), 1, (width, height))?;
        super::expect_len("image", out.len(), 3, (width, height))?;
        out.copy_from_slice(self.background.as_raw());
        if !indentation.iter().any(|m| *m > 0.0) {
            return Ok(());
        }
        let pixels = |index: usize| {
            let h = (f64::from(indentation[index]) / metres_per_pixel).max(0.0);
            if h.is_finite() { h } else { 0.0 }
        };
        surface::halve_into(pixels, indentation.len(), width, &mut buffers.heights);
        self.geometry.spread_and_place(
            &mut buffers.heights,
            (width, height),
            &mut buffers.scratch,
            &mut buffers.placed,
        );
        let RenderBuffers {
            heights,
            changes,
            columns,
            ..
        } = buffers;
        self.add_changes(heights, changes, columns, out);
        Ok(())
    }

    /// The image of the ball it was fitted with pressed at `centre` (column, row) with a press
    /// radius of `radius` pixels, as the presses it was fitted to are described.
    pub fn render_press(&self, centre: [f64; 2], radius: f64) -> RgbImage {
        let (width, height) = self.size();
        let heights = self.geometry.heights(width, height, centre, radius);
        let mut image = self.background.clone();
        self.add_changes(&heights, &mut Vec::new(), &mut Vec::new(), &mut image);
        image
    }

    /// Adds to `pixels` (the untouched gel's image) the colour changes of a spread
    /// half-resolution height map (pixels), computed into `changes` (per point of the grid)
    /// with `columns` (where each of the image's columns falls on the grid).
    fn add_changes(
        &self,
        heights: &[f64],
        changes: &mut Vec<[f32; 3]>,
        columns: &mut Vec<(usize, usize, f64)>,
        pixels: &mut [u8],
    ) {
        let (width, height) = self.size();
        let (half_width, half_height) = surface::half_size(width, height);
        let count = NORMAL_TERMS.len();
        changes.clear();
        changes.resize(heights.len(), [0.0; 3]);
        // The touched points' bounds on the grid: columns, then rows.
        let mut touched: Option<[usize; 4]> = None;
        surface::for_each_normal_terms(heights, half_width, |index, terms| {
            let terms = terms.map(|t| t as f32);
            let weights = &self.weights[index * 3 * count..(index + 1) * 3 * count];
            for (change, weights) in changes[index].iter_mut().zip(weights.chunks_exact(count)) {
                *change = terms.iter().zip(weights).map(|(t, w)| t * w).sum();
            }
            let (hx, hy) = (index % half_width, index / half_width);
            let [x0, x1, y0, y1] = touched.get_or_insert([hx, hx, hy, hy]);
            (*x0, *x1, *y0, *y1) = ((*x0).min(hx), (*x1).max(hx), (*y0).min(hy), (*y1).max(hy));
        });
        let Some([first_column, last_column, first_row, last_row]) = touched else {
            return;
        };
        columns.clear();
        columns.extend((0..width).map(|x| surface::between(x, half_width)));
        // The image's columns and rows that an untouched point's zero change alone reaches are
        // left as they are.
        let reached = |before: usize, after: usize, first: usize, last: usize| {
            after >= first && before <= last
        };
        for y in 0..height {
            let (y0, y1, fy) = surface::between(y, half_height);
            if !reached(y0, y1, first_row, last_row) {
                continue;
            }
            for (x, &(x0, x1, fx)) in columns.iter().enumerate() {
                if !reached(x0, x1, first_column, last_column) {
                    continue;
                }
                let corners = [
                    (changes[y0 * half_width + x0], (1.0 - fx) * (1.0 - fy)),
                    (changes[y0 * half_width + x1], fx * (1.0 - fy)),
                    (changes[y1 * half_width + x0], (1.0 - fx) * fy),
                    (changes[y1 * half_width + x1], fx * fy),
                ];
                for c in 0..3 {
                    let change: f32 = corners
                        .iter()
                        .map(|(change, weight)| change[c] * *weight as f32)
                        .sum();
                    let pixel = &mut pixels[(y * width + x) * 3 + c];
                    // Rounds half up: the sum is non-negative once clamped.
                    *pixel = (f32::from(*pixel) + change + 0.5).clamp(0.0, 255.0) as u8;
                }
            }
        }
    }
}

/// Whether `sensor` is a sensor's name a calibration may state: letters, digits, `_` and `-`.
///
/// ```
/// use yarok_components::tactile::calibration::check_sensor_name;
///
/// assert!(check_sensor_name("digit").is_ok() && check_sensor_name("../x").is_err());
/// ```
///
/// # Errors
///
/// A message naming the name, when it is not one.
pub fn check_sensor_name(sensor: &str) -> Result<(), FitError> {
    if !sensor.is_empty()
        && sensor.len() <= 64
        && sensor
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        Ok(())
    } else {
        Err(FitError::SensorName(sensor.to_owned()))
    }
}
