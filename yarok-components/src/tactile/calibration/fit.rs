//! Fitting a [`Calibration`] to real frames of ball presses.

use image::RgbImage;
use nalgebra::{DMatrix, SMatrix};

use super::press::{Press, within};
use super::surface::{
    Area, NORMAL_TERMS, POSITION_TERMS, between, half_normal_terms, half_position_terms, half_size,
    position_terms_of, spread,
};
use super::{
    Calibration, CalibrationError, Coverage, FitError, Geometry, PLACEMENT_LIMITS, Placement,
    SettingError,
};

/// Terms of the colour polynomial: every normal term times every position term.
const TERMS: usize = NORMAL_TERMS.len() * POSITION_TERMS.len();

/// How a calibration is fitted: the ball's size and the frames' scale, and the candidates
/// tried for the two geometric parameters (the one fitting the presses best is kept).
#[derive(Debug, Clone, PartialEq)]
pub struct FitSettings {
    /// The pressing ball's diameter, millimetres (FOTS' and Taxim's indenters: 4.70 mm).
    pub ball_diameter_mm: f64,
    /// The frames' scale at the gel, pixels per millimetre.
    pub pixels_per_mm: f64,
    /// Candidates for the contact circle's radius as a multiple of each press's radius (1 when
    /// the radii are contact circles; below 1 when they are visible imprints). Only those that
    /// keep every press's contact circle within the ball are tried: a ball cannot touch a circle
    /// wider than itself, and every press would be the ball sunk to its equator.
    pub contact_scales: Vec<f64>,
    /// Candidates for how far (Gaussian σ, pixels) the gel around a contact sinks with it.
    pub spreads: Vec<f64>,
    /// Where presses appear on the image from where they are described; `None` fits it: each
    /// press's image is moved to where it matches its frame best, and the placement explaining
    /// those moves kept (see [`Placement`]).
    pub placement: Option<Placement>,
}

impl Default for FitSettings {
    /// A 4.70 mm ball, 19.58 px/mm, contact scales 0.5 to 1 by 0.1, spreads 6 to 26 pixels by
    /// 4, the placement fitted.
    fn default() -> Self {
        Self {
            ball_diameter_mm: 4.7,
            pixels_per_mm: 19.58,
            contact_scales: vec![0.5, 0.6, 0.7, 0.8, 0.9, 1.0],
            spreads: vec![6.0, 10.0, 14.0, 18.0, 22.0, 26.0],
            placement: None,
        }
    }
}

impl FitSettings {
    /// Settings that keep `geometry` (another calibration's) and fit only how the sensor's
    /// surface becomes colour: for a sensor pressed like one already calibrated.
    ///
    /// ```
    /// use yarok_components::tactile::calibration::{Calibration, FitSettings};
    ///
    /// let like_the_digit = FitSettings::with_geometry(&Calibration::digit().geometry());
    /// assert_eq!(like_the_digit.spreads, [Calibration::digit().geometry().spread]);
    /// ```
    pub fn with_geometry(geometry: &Geometry) -> Self {
        Self {
            ball_diameter_mm: geometry.ball_diameter_mm,
            pixels_per_mm: geometry.pixels_per_mm,
            contact_scales: vec![geometry.contact_scale],
            spreads: vec![geometry.spread],
            placement: Some(geometry.placement),
        }
    }
}

/// Within how many radii of its centre a press changes its frame: beyond, the frame shows the
/// untouched gel (and helps estimate it); within, its pixels are what the colour model is fitted
/// to. Pixels further out would fit only the camera's noise and the gel's drift: a flat gel has
/// no slope terms, so the model's change there is nothing by construction.
const FAR_FIELD: f64 = 1.8;
/// Within how many radii of its centre a press's fit is scored (the fidelity protocol's
/// contact region).
const SCORED: f64 = 1.5;
/// How much the background estimated from the frames is smoothed (σ, pixels): the untouched
/// gel's look changes over tens of pixels (its lights, its paint), the camera's noise from pixel
/// to pixel, and the few frames averaged leave much of it; twice as much begins to blur the
/// DIGIT's gel.
const BACKGROUND_SMOOTHING: f64 = 4.0;
/// Ridge regularisation, relative to the normal equations' mean diagonal.
const RIDGE: f64 = 1e-3;

/// Fits a calibration to an untouched frame and presses (see [`Calibration::fit`]).
pub(super) fn fit(
    untouched: &RgbImage,
    presses: &[Press],
    settings: &FitSettings,
) -> Result<Calibration, CalibrationError> {
    check(untouched, presses, settings)?;
    let background = background(untouched, presses);
    let noise = camera_noise(&background, presses);
    let covered = Coverage::of(presses, untouched.width(), untouched.height()).area();
    let fitted = |geometry: Geometry| {
        let coefficients = coefficients(&background, presses, &geometry, &covered)?;
        Calibration::new(background.clone(), geometry, coefficients, noise, covered)
    };
    let mut best: Option<(f64, Calibration)> = None;
    for contact_scale in possible_contact_scales(presses, settings)? {
        for &spread in &settings.spreads {
            let calibration = fitted(Geometry {
                pixels_per_mm: settings.pixels_per_mm,
                ball_diameter_mm: settings.ball_diameter_mm,
                contact_scale,
                spread,
                placement: settings.placement.unwrap_or_default(),
            })?;
            let error = mean_error(&calibration, presses);
            if best.as_ref().is_none_or(|(least, _)| error < *least) {
                best = Some((error, calibration));
            }
        }
    }
    let mut calibration = best.expect("checked: at least one candidate").1;
    if settings.placement.is_none() {
        for _ in 0..PLACEMENT_ROUNDS {
            let (width, height) = calibration.size();
            let moves: Vec<([f64; 2], [f64; 2])> = presses
                .iter()
                .map(|press| (press.centre, best_move(&calibration, press)))
                .collect();
            let mut geometry = calibration.geometry();
            let found = Placement::fit(&moves, width, height);
            geometry.placement = geometry.placement.after_moves(&found);
            geometry
                .placement
                .check()
                .map_err(FitError::FarFromCentres)?;
            calibration = fitted(geometry)?;
        }
    }
    Ok(calibration)
}

/// Rounds of fitting the placement: each moves every press's image to where it matches its frame
/// best and refits the colour model there.
const PLACEMENT_ROUNDS: usize = 2;

/// The steps (pixels) by which [`best_move`] searches, coarse to fine.
const MOVE_STEPS: [f64; 4] = [4.0, 2.0, 1.0, 0.5];

/// [`Calibration::best_move`]: a descent on a grid refined by [`MOVE_STEPS`], scored within
/// [`SCORED`] radii, never further than a placement's largest offset each way.
pub(super) fn best_move(calibration: &Calibration, press: &Press) -> [f64; 2] {
    let error_at = |offset: [f64; 2]| {
        let centre = [press.centre[0] + offset[0], press.centre[1] + offset[1]];
        scored_error(&calibration.render_press(centre, press.radius), press)
    };
    let mut best = ([0.0; 2], error_at([0.0; 2]));
    for step in MOVE_STEPS {
        loop {
            let around = best.0;
            for (dx, dy) in [(-1.0, -1.0), (0.0, -1.0), (1.0, -1.0), (-1.0, 0.0)]
                .into_iter()
                .chain([(1.0, 0.0), (-1.0, 1.0), (0.0, 1.0), (1.0, 1.0)])
            {
                let offset = [around[0] + dx * step, around[1] + dy * step];
                if offset.iter().any(|o| o.abs() > PLACEMENT_LIMITS[0]) {
                    continue;
                }
                let error = error_at(offset);
                if error < best.1 {
                    best = (offset, error);
                }
            }
            if best.0 == around {
                break;
            }
        }
    }
    best.0
}

/// The candidate contact scales of `settings` that keep every press's contact circle within
/// the ball.
///
/// # Errors
///
/// When none does: naming the widest press, the ball and the largest scale they allow.
fn possible_contact_scales(
    presses: &[Press],
    settings: &FitSettings,
) -> Result<Vec<f64>, CalibrationError> {
    let ball_radius = settings.ball_diameter_mm * settings.pixels_per_mm / 2.0;
    let widest = presses.iter().map(|p| p.radius).fold(0.0, f64::max);
    let possible: Vec<f64> = settings
        .contact_scales
        .iter()
        .copied()
        .filter(|scale| scale * widest <= ball_radius)
        .collect();
    if possible.is_empty() {
        return Err(FitError::ContactWiderThanBall {
            tried: settings.contact_scales.clone(),
            widest_pixels: widest,
            ball_diameter_mm: settings.ball_diameter_mm,
            ball_radius_pixels: ball_radius,
            pixels_per_mm: settings.pixels_per_mm,
        }
        .into());
    }
    Ok(possible)
}

fn check(
    untouched: &RgbImage,
    presses: &[Press],
    settings: &FitSettings,
) -> Result<(), CalibrationError> {
    if presses.is_empty() {
        return Err(FitError::NoPresses.into());
    }
    if let Some((index, press)) = presses
        .iter()
        .enumerate()
        .find(|(_, p)| p.frame.dimensions() != untouched.dimensions())
    {
        return Err(FitError::FrameSize {
            press: index,
            size: [press.frame.width(), press.frame.height()],
            untouched: [untouched.width(), untouched.height()],
        }
        .into());
    }
    if let Some(index) = presses.iter().position(|p| {
        !(p.radius.is_finite() && p.radius > 0.0 && p.centre.iter().all(|c| c.is_finite()))
    }) {
        return Err(FitError::PressShape { press: index }.into());
    }
    let named = [
        ("ball_diameter_mm", vec![settings.ball_diameter_mm]),
        ("pixels_per_mm", vec![settings.pixels_per_mm]),
        ("contact_scale", settings.contact_scales.clone()),
        ("spread_pixels", settings.spreads.clone()),
    ];
    for (name, values) in named {
        if values.is_empty() {
            return Err(FitError::NothingToTry { setting: name }.into());
        }
        for value in values {
            check_setting(name, value).map_err(FitError::from)?;
        }
    }
    Ok(())
}

/// Each calibration setting's physically meaningful range, by the name a calibration file
/// gives it: what `calibrate` accepts and a calibration file may hold. The spread's bound also
/// bounds the fit's cost, which grows with it.
pub const SETTING_RANGES: [(&str, [f64; 2]); 4] = [
    ("ball_diameter_mm", [0.5, 50.0]),
    ("pixels_per_mm", [1.0, 200.0]),
    ("contact_scale", [0.05, 3.0]),
    ("spread_pixels", [0.0, 64.0]),
];

/// Whether calibration setting `name` (one of [`SETTING_RANGES`]) may be `value`; the refusal
/// names the setting, the value and the range.
///
/// # Errors
///
/// When `value` is outside the setting's range or not a number.
pub fn check_setting(name: &str, value: f64) -> Result<(), SettingError> {
    let Some((known, [lowest, highest])) = SETTING_RANGES.iter().find(|(known, _)| *known == name)
    else {
        return Err(SettingError::Unknown(name.to_owned()));
    };
    if (*lowest..=*highest).contains(&value) {
        return Ok(());
    }
    Err(SettingError::OutOfRange {
        name: known,
        value,
        lowest: *lowest,
        highest: *highest,
    })
}

/// The untouched gel: per pixel, the mean of the untouched frame and of the presses' frames
/// where they are far from their press (averaging out the camera's noise), slightly smoothed.
fn background(untouched: &RgbImage, presses: &[Press]) -> RgbImage {
    let (width, height) = (untouched.width() as usize, untouched.height() as usize);
    let mut channels: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; width * height]);
    for (index, pixel) in untouched.pixels().enumerate() {
        let (x, y) = (index % width, index / width);
        let mut count = 1.0;
        let mut sum = pixel.0.map(f64::from);
        for press in presses.iter().filter(|p| !within(p, x, y, FAR_FIELD)) {
            let seen = press.frame.get_pixel(x as u32, y as u32).0;
            for (sum, seen) in sum.iter_mut().zip(seen) {
                *sum += f64::from(seen);
            }
            count += 1.0;
        }
        for (channel, sum) in channels.iter_mut().zip(sum) {
            channel[index] = sum / count;
        }
    }
    for channel in &mut channels {
        spread(channel, width, BACKGROUND_SMOOTHING);
    }
    RgbImage::from_fn(width as u32, height as u32, |x, y| {
        let index = y as usize * width + x as usize;
        image::Rgb(
            channels
                .each_ref()
                .map(|c| c[index].round().clamp(0.0, 255.0) as u8),
        )
    })
}

/// The camera's noise: per channel, the standard deviation of the presses' frames from the
/// untouched gel far from their press (each frame's own mean offset removed), levels.
fn camera_noise(background: &RgbImage, presses: &[Press]) -> [f64; 3] {
    let mut squares = [0.0; 3];
    let mut count = 0usize;
    for press in presses {
        let far: Vec<[f64; 3]> = press
            .frame
            .enumerate_pixels()
            .filter(|(x, y, _)| !within(press, *x as usize, *y as usize, FAR_FIELD))
            .map(|(x, y, seen)| {
                let untouched = background.get_pixel(x, y);
                std::array::from_fn(|c| f64::from(seen[c]) - f64::from(untouched[c]))
            })
            .collect();
        let n = far.len().max(1) as f64;
        let mean: [f64; 3] = std::array::from_fn(|c| far.iter().map(|d| d[c]).sum::<f64>() / n);
        for difference in &far {
            for c in 0..3 {
                squares[c] += (difference[c] - mean[c]).powi(2);
            }
        }
        count += far.len();
    }
    squares.map(|sum| (sum / count.max(1) as f64).sqrt())
}

/// The colour polynomial's coefficients (per term, R, G and B) that fit the presses' change
/// from the background best in the least-squares sense (ridge-regularised).
fn coefficients(
    background: &RgbImage,
    presses: &[Press],
    geometry: &Geometry,
    covered: &Area,
) -> Result<Vec<[f64; 3]>, CalibrationError> {
    let (width, height) = (background.width() as usize, background.height() as usize);
    let mut normal = DMatrix::<f64>::zeros(TERMS, TERMS);
    let mut target = DMatrix::<f64>::zeros(TERMS, 3);
    let (half_width, half_height) = half_size(width, height);
    let positions: Vec<[f64; 6]> = (0..half_width * half_height)
        .map(|i| half_position_terms(i % half_width, i / half_width, width, height, covered))
        .collect();
    let columns: Vec<_> = (0..width).map(|x| between(x, half_width)).collect();
    let mut terms = [0.0; TERMS];
    for press in presses {
        let normals = half_normal_terms(
            &geometry.heights(width, height, press.centre, press.radius),
            half_width,
        );
        for y in 0..height {
            let (y0, y1, fy) = between(y, half_height);
            for (x, &(x0, x1, fx)) in columns.iter().enumerate() {
                if !within(press, x, y, FAR_FIELD) {
                    continue;
                }
                // The image's terms: the grid's, interpolated as the model's changes are.
                terms.fill(0.0);
                for (corner, weight) in [
                    (y0 * half_width + x0, (1.0 - fx) * (1.0 - fy)),
                    (y0 * half_width + x1, fx * (1.0 - fy)),
                    (y1 * half_width + x0, (1.0 - fx) * fy),
                    (y1 * half_width + x1, fx * fy),
                ] {
                    let Some(grid_terms) = &normals[corner] else {
                        continue;
                    };
                    for (k, n) in grid_terms.iter().enumerate() {
                        let positions = &positions[corner][..position_terms_of(k)];
                        for (q, p) in positions.iter().enumerate() {
                            terms[k * POSITION_TERMS.len() + q] += weight * n * p;
                        }
                    }
                }
                let (seen, untouched) = (
                    press.frame.get_pixel(x as u32, y as u32).0,
                    background.get_pixel(x as u32, y as u32).0,
                );
                for i in 0..TERMS {
                    for j in i..TERMS {
                        normal[(i, j)] += terms[i] * terms[j];
                    }
                    for c in 0..3 {
                        target[(i, c)] += terms[i] * (f64::from(seen[c]) - f64::from(untouched[c]));
                    }
                }
            }
        }
    }
    let ridge = RIDGE * normal.trace() / TERMS as f64;
    for i in 0..TERMS {
        normal[(i, i)] += ridge;
        for j in 0..i {
            normal[(i, j)] = normal[(j, i)];
        }
    }
    let solution = normal
        .cholesky()
        .ok_or(FitError::Undetermined)?
        .solve(&target);
    Ok((0..TERMS)
        .map(|i| {
            let row: SMatrix<f64, 1, 3> = solution.fixed_view::<1, 3>(i, 0).into_owned();
            [row[0], row[1], row[2]]
        })
        .collect())
}

/// Mean absolute error (levels) of the calibration's images of the presses within their
/// scored regions.
fn mean_error(calibration: &Calibration, presses: &[Press]) -> f64 {
    let sums = presses.iter().map(|press| {
        let image = calibration.render_press(press.centre, press.radius);
        scored_sum(&image, press)
    });
    let (sum, count) = sums.fold((0.0, 0usize), |(s, c), (sum, count)| (s + sum, c + count));
    sum / count.max(1) as f64
}

/// Mean absolute error (levels) of `image` from `press`'s frame within its scored region.
fn scored_error(image: &RgbImage, press: &Press) -> f64 {
    let (sum, count) = scored_sum(image, press);
    sum / count.max(1) as f64
}

/// The absolute differences (levels) of `image` from `press`'s frame within its scored region:
/// their sum and how many values.
fn scored_sum(image: &RgbImage, press: &Press) -> (f64, usize) {
    let (mut sum, mut count) = (0.0, 0usize);
    for (x, y, pixel) in image.enumerate_pixels() {
        if within(press, x as usize, y as usize, SCORED) {
            let seen = press.frame.get_pixel(x, y).0;
            sum += pixel
                .0
                .iter()
                .zip(seen)
                .map(|(a, b)| f64::from(a.abs_diff(b)))
                .sum::<f64>();
            count += 3;
        }
    }
    (sum, count)
}
