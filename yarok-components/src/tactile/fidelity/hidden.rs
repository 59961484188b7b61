//! What the medians of [`Scores`] hide: where on the gel a model holds, whether its images
//! change with the press's depth as the real frames do, whether it extrapolates evenly, and how
//! near the data's own ceiling its whole-image SSIM is.

use image::RgbImage;

use super::{Disc, Scores, compare, pearson};
use crate::tactile::calibration::{Calibration, Press};

/// A part of the gel, the gel cut in thirds each way.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Band {
    /// The middle third both ways.
    Centre,
    /// The middle third one way, an outer third the other.
    Edges,
    /// An outer third both ways.
    Corners,
}

impl Band {
    /// Every band, centre first.
    pub const ALL: [Band; 3] = [Band::Centre, Band::Edges, Band::Corners];

    /// The band of a `width × height` gel that `point` (column, row, pixels) is in.
    ///
    /// ```
    /// use yarok_components::tactile::fidelity::Band;
    ///
    /// assert_eq!(Band::of([120.0, 160.0], 240, 320), Band::Centre);
    /// assert_eq!(Band::of([10.0, 160.0], 240, 320), Band::Edges);
    /// assert_eq!(Band::of([230.0, 300.0], 240, 320), Band::Corners);
    /// ```
    pub fn of(point: [f64; 2], width: u32, height: u32) -> Self {
        let third = |at: f64, size: u32| (3.0 * at / f64::from(size)).clamp(0.0, 2.0) as u32;
        match (third(point[0], width), third(point[1], height)) {
            (1, 1) => Band::Centre,
            (0 | 2, 0 | 2) => Band::Corners,
            _ => Band::Edges,
        }
    }

    /// Its name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Band::Centre => "centre",
            Band::Edges => "edge bands",
            Band::Corners => "corners",
        }
    }
}

/// Per band of a `width × height` gel, the median over `presses` (in a band) of their scores'
/// mean change correlation, and how many presses are in it; `None` for a band with none.
/// `scores` are the presses' scores, in order.
pub fn change_correlation_by_band(
    presses: &[Press],
    scores: &[Scores],
    width: u32,
    height: u32,
) -> [(Band, Option<f64>, usize); 3] {
    Band::ALL.map(|band| {
        let in_band: Vec<f64> = presses
            .iter()
            .zip(scores)
            .filter(|(press, _)| Band::of(press.centre, width, height) == band)
            .map(|(_, scores)| scores.mean_change_correlation())
            .collect();
        let count = in_band.len();
        (band, median_of(in_band), count)
    })
}

/// Pairs of `presses` whose centres are within `within` pixels of each other and whose radii
/// differ by what `radii` accepts (the difference, pixels).
fn nearby_pairs<'a>(
    presses: &[&'a Press],
    within: f64,
    radii: impl Fn(f64) -> bool,
) -> Vec<(&'a Press, &'a Press)> {
    let mut found = Vec::new();
    for (i, a) in presses.iter().enumerate() {
        for b in &presses[i + 1..] {
            let apart = (a.centre[0] - b.centre[0]).hypot(a.centre[1] - b.centre[1]);
            if apart <= within && radii((a.radius - b.radius).abs()) {
                found.push((*a, *b));
            }
        }
    }
    found
}

/// How a model's images change with the press's depth as the real frames do: over the pairs of
/// `presses` within 6 px of each other whose radii differ by 1.5 px or more, the median
/// correlation of the simulated difference (`render`'s images of the two) with the real one,
/// within 1.5 of the larger radius; and how many pairs there were (`None` for none).
pub fn depth_sensitivity(
    presses: &[&Press],
    mut render: impl FnMut(&Press) -> RgbImage,
) -> (Option<f64>, usize) {
    let pairs = nearby_pairs(presses, 6.0, |difference| difference >= 1.5);
    let correlations = pairs
        .iter()
        .map(|(a, b)| {
            let radius = 1.5 * a.radius.max(b.radius);
            let real = difference(&a.frame, &b.frame, a.centre, radius);
            let simulated = difference(&render(a), &render(b), a.centre, radius);
            pearson_of(&real, &simulated)
        })
        .collect();
    (median_of(correlations), pairs.len())
}

/// How evenly a flat press `depth_m` metres deep over the whole gel changes the calibration's
/// image: the largest change of a pixel (levels, its most changed channel) and the median
/// change. An even press changes every pixel alike.
pub fn flat_press_changes(calibration: &Calibration, depth_m: f32) -> (f64, f64) {
    let metres_per_pixel = 1e-3 / calibration.geometry().pixels_per_mm;
    let (width, height) = calibration.size();
    let flat = calibration
        .render_indentation(&vec![depth_m; width * height], metres_per_pixel)
        .expect("a map of the image's size");
    let changes: Vec<f64> = flat
        .pixels()
        .zip(calibration.background().pixels())
        .map(|(p, q)| {
            (0..3)
                .map(|c| f64::from(p[c].abs_diff(q[c])))
                .fold(0.0, f64::max)
        })
        .collect();
    let largest = changes.iter().copied().fold(0.0, f64::max);
    (largest, median_of(changes).unwrap_or(0.0))
}

/// The whole-image SSIM the data itself allows: the median, over pairs of `presses` of one spot
/// (centres within 5 px, radii within 1.5 px), of one frame against the other smoothed by a
/// Gaussian of σ 1 px (a simulated image has no camera noise); and how many pairs there were.
pub fn ssim_ceiling(presses: &[&Press], untouched: &RgbImage) -> (Option<f64>, usize) {
    let pairs = nearby_pairs(presses, 5.0, |difference| difference <= 1.5);
    let scores = pairs
        .iter()
        .map(|(a, b)| {
            let disc = Disc {
                centre: a.centre,
                radius: 1.5 * a.radius,
            };
            let smoothed = image::imageops::blur(&b.frame, 1.0);
            compare(&a.frame, untouched, &smoothed, untouched, disc).whole_ssim
        })
        .collect();
    (median_of(scores), pairs.len())
}

/// `a − b` over the pixels within `radius` of `centre`, every channel.
fn difference(a: &RgbImage, b: &RgbImage, centre: [f64; 2], radius: f64) -> Vec<f64> {
    let disc = Disc { centre, radius };
    a.enumerate_pixels()
        .filter(|(x, y, _)| disc.contains(*x as usize, *y as usize))
        .flat_map(|(x, y, p)| {
            let q = b.get_pixel(x, y);
            (0..3).map(move |c| f64::from(p[c]) - f64::from(q[c]))
        })
        .collect()
}

fn pearson_of(a: &[f64], b: &[f64]) -> f64 {
    let pairs: Vec<(f64, f64)> = a.iter().copied().zip(b.iter().copied()).collect();
    pearson(&pairs)
}

/// The median of `values` (the mean of the middle two for an even count), `None` for none.
fn median_of(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    (n > 0).then(|| (values[(n - 1) / 2] + values[n / 2]) / 2.0)
}
