//! How closely a simulated tactile image matches a real one, by the measures the field reports:
//! SSIM (as `skimage.metrics.structural_similarity` computes it with its defaults: 7 × 7 uniform
//! windows, sample covariance, `data_range` 255, channels averaged), mean absolute error and
//! PSNR, over the whole image and over the contact region (a disc around the press), and the
//! Pearson correlation of the change a press makes (frame − untouched frame against simulated −
//! simulated untouched) per channel.
//!
//! ```
//! use image::RgbImage;
//! use yarok_components::tactile::fidelity::{Disc, compare};
//!
//! let real = RgbImage::from_fn(40, 30, |x, y| image::Rgb([(x * 6) as u8, (y * 8) as u8, 90]));
//! let scores = compare(&real, &real, &real, &real, Disc { centre: [20.0, 15.0], radius: 8.0 });
//! assert!((scores.whole_ssim - 1.0).abs() < 1e-12);
//! assert_eq!(scores.contact_mae, 0.0);
//! ```

mod hidden;

use image::RgbImage;

pub use hidden::{
    Band, change_correlation_by_band, depth_sensitivity, flat_press_changes, ssim_ceiling,
};

use super::calibration::{Geometry, Press};
use super::filter::reflect;
use super::phong::PhongModel;

/// SSIM's window: 7 × 7 pixels.
const WINDOW: usize = 7;

/// A disc of the image: centre (column, row) and radius, pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    /// Centre: column, row.
    pub centre: [f64; 2],
    /// Radius, pixels.
    pub radius: f64,
}

impl Disc {
    fn contains(&self, x: usize, y: usize) -> bool {
        let dx = x as f64 + 0.5 - self.centre[0];
        let dy = y as f64 + 0.5 - self.centre[1];
        dx * dx + dy * dy < self.radius * self.radius
    }
}

/// The scores of a simulated image against a real one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scores {
    /// SSIM over the whole image (the map's mean without its 3-pixel border, as skimage).
    pub whole_ssim: f64,
    /// The SSIM map's mean over the contact disc.
    pub contact_ssim: f64,
    /// Mean absolute error over the whole image, levels 0–255.
    pub whole_mae: f64,
    /// Mean absolute error over the contact disc, levels.
    pub contact_mae: f64,
    /// PSNR over the whole image, dB.
    pub whole_psnr: f64,
    /// PSNR over the contact disc, dB.
    pub contact_psnr: f64,
    /// Pearson correlation of the changes over the contact disc, R, G, B (0 where the simulated
    /// change is constant).
    pub change_correlation: [f64; 3],
}

impl Scores {
    /// The mean of [`Scores::change_correlation`] over the channels.
    pub fn mean_change_correlation(&self) -> f64 {
        self.change_correlation.iter().sum::<f64>() / 3.0
    }
}

/// Scores `simulated` (whose untouched image is `simulated_untouched`) against `real` (whose
/// untouched frame is `real_untouched`), the contact region being `contact`. All four images
/// must be the same size, at least 7 × 7.
///
/// # Panics
///
/// If the sizes differ or are below 7 × 7.
pub fn compare(
    real: &RgbImage,
    real_untouched: &RgbImage,
    simulated: &RgbImage,
    simulated_untouched: &RgbImage,
    contact: Disc,
) -> Scores {
    let size = real.dimensions();
    assert!(
        [real_untouched, simulated, simulated_untouched]
            .iter()
            .all(|i| i.dimensions() == size)
            && size.0 as usize >= WINDOW
            && size.1 as usize >= WINDOW,
        "images of one size, at least 7 × 7"
    );
    let (width, height) = (size.0 as usize, size.1 as usize);
    let map = ssim_map(real, simulated);
    let pad = (WINDOW - 1) / 2;
    let mut whole = Mean::default();
    let mut disc = Mean::default();
    for y in 0..height {
        for x in 0..width {
            let value = map[y * width + x];
            if (pad..width - pad).contains(&x) && (pad..height - pad).contains(&y) {
                whole.add(value);
            }
            if contact.contains(x, y) {
                disc.add(value);
            }
        }
    }
    let mut errors = [Mean::default(), Mean::default()];
    let mut squared = [Mean::default(), Mean::default()];
    let mut changes: [Vec<(f64, f64)>; 3] = Default::default();
    for (index, (a, b)) in real.pixels().zip(simulated.pixels()).enumerate() {
        let (x, y) = (index % width, index / width);
        let inside = contact.contains(x, y);
        for c in 0..3 {
            let error = f64::from(a[c]) - f64::from(b[c]);
            for (region, wanted) in [(0, true), (1, inside)] {
                if wanted {
                    errors[region].add(error.abs());
                    squared[region].add(error * error);
                }
            }
            if inside {
                let real_change =
                    f64::from(a[c]) - f64::from(real_untouched.as_raw()[index * 3 + c]);
                let simulated_change =
                    f64::from(b[c]) - f64::from(simulated_untouched.as_raw()[index * 3 + c]);
                changes[c].push((real_change, simulated_change));
            }
        }
    }
    let psnr = |mse: f64| 10.0 * (255.0 * 255.0 / mse).log10();
    Scores {
        whole_ssim: whole.value(),
        contact_ssim: disc.value(),
        whole_mae: errors[0].value(),
        contact_mae: errors[1].value(),
        whole_psnr: psnr(squared[0].value()),
        contact_psnr: psnr(squared[1].value()),
        change_correlation: changes.each_ref().map(|pairs| pearson(pairs)),
    }
}

/// A running mean.
#[derive(Default)]
struct Mean {
    sum: f64,
    count: usize,
}

impl Mean {
    fn add(&mut self, value: f64) {
        self.sum += value;
        self.count += 1;
    }

    fn value(&self) -> f64 {
        self.sum / self.count.max(1) as f64
    }
}

/// Pearson's correlation of the pairs (0 if either side is constant).
fn pearson(pairs: &[(f64, f64)]) -> f64 {
    let n = pairs.len().max(1) as f64;
    let (ma, mb) = pairs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in pairs {
        ab += (x - ma) * (y - mb);
        aa += (x - ma) * (x - ma);
        bb += (y - mb) * (y - mb);
    }
    if aa == 0.0 || bb == 0.0 {
        0.0
    } else {
        ab / (aa * bb).sqrt()
    }
}

/// The SSIM map of two images, per pixel the mean over the channels (skimage's defaults).
fn ssim_map(a: &RgbImage, b: &RgbImage) -> Vec<f64> {
    let (width, height) = (a.width() as usize, a.height() as usize);
    let (c1, c2) = ((0.01f64 * 255.0).powi(2), (0.03f64 * 255.0).powi(2));
    let samples = (WINDOW * WINDOW) as f64;
    let covariance = samples / (samples - 1.0);
    let mut map = vec![0.0; width * height];
    for c in 0..3 {
        let channel =
            |image: &RgbImage| -> Vec<f64> { image.pixels().map(|p| f64::from(p[c])).collect() };
        let (x, y) = (channel(a), channel(b));
        let product =
            |p: &[f64], q: &[f64]| -> Vec<f64> { p.iter().zip(q).map(|(p, q)| p * q).collect() };
        let [ux, uy, uxx, uyy, uxy] = [
            x.clone(),
            y.clone(),
            product(&x, &x),
            product(&y, &y),
            product(&x, &y),
        ]
        .map(|values| uniform_filter(values, width));
        for (i, value) in map.iter_mut().enumerate() {
            let vx = covariance * (uxx[i] - ux[i] * ux[i]);
            let vy = covariance * (uyy[i] - uy[i] * uy[i]);
            let vxy = covariance * (uxy[i] - ux[i] * uy[i]);
            let ssim = ((2.0 * ux[i] * uy[i] + c1) * (2.0 * vxy + c2))
                / ((ux[i] * ux[i] + uy[i] * uy[i] + c1) * (vx + vy + c2));
            *value += ssim / 3.0;
        }
    }
    map
}

/// SciPy's `uniform_filter` of size 7 (its default `reflect` border, `dcba|abcd|dcba`) of a
/// row-major map.
fn uniform_filter(mut values: Vec<f64>, width: usize) -> Vec<f64> {
    let height = values.len() / width;
    let radius = (WINDOW / 2) as i64;
    let mut line = Vec::new();
    let mut pass = |values: &mut [f64], len: usize, stride: usize| {
        line.clear();
        line.extend(values.iter().step_by(stride).take(len).copied());
        for i in 0..len as i64 {
            let sum: f64 = (i - radius..=i + radius)
                .map(|j| line[reflect(j, len as i64) as usize])
                .sum();
            values[i as usize * stride] = sum / WINDOW as f64;
        }
    };
    for y in 0..height {
        pass(&mut values[y * width..(y + 1) * width], width, 1);
    }
    for x in 0..width {
        pass(&mut values[x..], height, width);
    }
    values
}

/// The scores of a model's images of `presses` against their frames (see [`compare`]), the
/// contact region each press's disc of 1.5 radii (the fidelity protocol's): `render` gives the
/// model's image of a press, `simulated_untouched` its image of the untouched gel.
pub fn score(
    real_untouched: &RgbImage,
    simulated_untouched: &RgbImage,
    presses: &[Press],
    mut render: impl FnMut(&Press) -> RgbImage,
) -> Vec<Scores> {
    presses
        .iter()
        .map(|press| {
            let contact = Disc {
                centre: press.centre,
                radius: 1.5 * press.radius,
            };
            compare(
                &press.frame,
                real_untouched,
                &render(press),
                simulated_untouched,
                contact,
            )
        })
        .collect()
}

/// The median of each score over `scores` (the mean of the middle two for an even count).
///
/// # Panics
///
/// If `scores` is empty.
pub fn median(scores: &[Scores]) -> Scores {
    let middle = |pick: &dyn Fn(&Scores) -> f64| {
        let mut values: Vec<f64> = scores.iter().map(pick).collect();
        values.sort_by(f64::total_cmp);
        let n = values.len();
        (values[(n - 1) / 2] + values[n / 2]) / 2.0
    };
    Scores {
        whole_ssim: middle(&|s| s.whole_ssim),
        contact_ssim: middle(&|s| s.contact_ssim),
        whole_mae: middle(&|s| s.whole_mae),
        contact_mae: middle(&|s| s.contact_mae),
        whole_psnr: middle(&|s| s.whole_psnr),
        contact_psnr: middle(&|s| s.contact_psnr),
        change_correlation: std::array::from_fn(|c| middle(&|s| s.change_correlation[c])),
    }
}

/// A Phong model's image of a press (the reference models' way: a depth map in metres, the
/// model deforming the gel itself), or of the untouched gel (`press` `None`): the ball of
/// `geometry` pressed into a gel whose untouched surface is `surface` metres from the camera, by
/// the press's contact circle, seen over `background`.
///
/// # Panics
///
/// If `background` is not the model's image size for its own size of depth map.
pub fn phong_image(
    model: &mut PhongModel,
    surface: f64,
    geometry: &Geometry,
    press: Option<&Press>,
    background: &RgbImage,
) -> RgbImage {
    let (width, height) = (background.width() as usize, background.height() as usize);
    let depth = phong_depth(surface, geometry, press, width, height);
    let pixels = model
        .render(&depth, width, background.as_raw())
        .expect("a depth map and background of one size");
    RgbImage::from_raw(width as u32, height as u32, pixels).expect("the model's image size")
}

/// The depth map (metres) [`phong_image`] renders.
pub fn phong_depth(
    surface: f64,
    geometry: &Geometry,
    press: Option<&Press>,
    width: usize,
    height: usize,
) -> Vec<f32> {
    let Some(press) = press else {
        return vec![surface as f32; width * height];
    };
    let metres_per_pixel = 1e-3 / geometry.pixels_per_mm;
    geometry
        .press(width, height, press.centre, press.radius)
        .iter()
        .map(|h| (surface - h * metres_per_pixel) as f32)
        .collect()
}
