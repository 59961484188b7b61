//! Sim-to-real: a contact localiser (a ridge regression from the press's change image to its centre
//! and radius) trained **only** on images a model renders — the DIGIT's bundled calibration, or the
//! reference Phong model over the same untouched gel, each with fresh noise at the calibrated
//! camera's levels (yarok's sensor adds a fixed pattern of the same) — at random centres and radii,
//! then tested on the real DIGIT's 21 frames of ball presses
//! (`yarok-components/data/tactile-real/digit`); beside them, the same localiser trained on the
//! real frames themselves, each left out in turn. Every change is taken from the calibration's
//! untouched gel (the data's untouched frame averaged with the calibration frames away from their
//! press), as a sensor in use takes it from a reference frame of the day: the data's untouched
//! frame alone was taken apart from the presses, and the gel's look drifted between them (a haze
//! along the top of the frame). Prints the median and the largest error of the centre and of the
//! radius, pixels; and, first, where the real frames' change lies against their labelled centres,
//! where yarok's images of the same presses put theirs, and how far yarok's image of each real
//! press must move to match the frame best.
//!
//! ```text
//! cargo bench --bench tactile_localiser
//! ```

use image::RgbImage;
use yarok::components::tactile::calibration::{
    Calibration, Placement, Press, held_out, read_presses,
};
use yarok::components::tactile::fidelity;
use yarok::components::tactile::noise::CameraNoise;
use yarok::components::tactile::phong::{PhongModel, PhongParams};
use yarok::nalgebra::{DMatrix, DVector};
use yarok_test::generator::Generator;

/// Images rendered to train on (6 000 give a median within 0.1 px of these).
const TRAINING: usize = 10_000;

/// Every how many presses one is held out from the bundled calibration.
const HOLD_OUT: u32 = 3;

/// Pixels averaged into one feature, each way.
const BLOCK: u32 = 10;

/// A pixel's change (levels, summed over its channels) below which it counts as the camera's
/// noise, not the press.
const NOISE_FLOOR: f64 = 20.0;

/// Ridge regularisation, relative to the normal equations' mean diagonal.
const RIDGE: f64 = 1e-3;

/// How much a pixel changed from the untouched gel beyond the camera's noise: its channels'
/// absolute changes summed, less [`NOISE_FLOOR`], at least zero.
fn change_beyond_noise(seen: &image::Rgb<u8>, untouched: &image::Rgb<u8>) -> f64 {
    let change: f64 = (0..3)
        .map(|c| (f64::from(seen[c]) - f64::from(untouched[c])).abs())
        .sum();
    (change - NOISE_FLOOR).max(0.0)
}

/// The features of a press's frame: its change from the untouched gel, per block of
/// [`BLOCK`] × [`BLOCK`] pixels, beyond the camera's noise ([`NOISE_FLOOR`]), normalised to sum to one (so that
/// the centre is near a linear function of them), and the change's total size.
fn features(frame: &RgbImage, untouched: &RgbImage) -> Vec<f64> {
    let (width, height) = frame.dimensions();
    let (columns, rows) = (width / BLOCK, height / BLOCK);
    let mut blocks = vec![0.0; (columns * rows) as usize];
    for (x, y, seen) in frame.enumerate_pixels() {
        let (bx, by) = (x / BLOCK, y / BLOCK);
        if bx >= columns || by >= rows {
            continue;
        }
        blocks[(by * columns + bx) as usize] +=
            change_beyond_noise(seen, untouched.get_pixel(x, y));
    }
    let total: f64 = blocks.iter().sum::<f64>().max(1.0);
    let mut features: Vec<f64> = blocks.iter().map(|b| b / total).collect();
    features.push((total / f64::from(width * height)).sqrt());
    features.push(1.0);
    features
}

/// Where a press's change lies: the centroid (column, row) of its pixels' change beyond the
/// camera's noise ([`NOISE_FLOOR`]), weighted by it.
fn change_centroid(frame: &RgbImage, untouched: &RgbImage) -> [f64; 2] {
    let (mut sum, mut weights) = ([0.0; 2], 0.0);
    for (x, y, seen) in frame.enumerate_pixels() {
        let weight = change_beyond_noise(seen, untouched.get_pixel(x, y));
        sum[0] += weight * (f64::from(x) + 0.5);
        sum[1] += weight * (f64::from(y) + 0.5);
        weights += weight;
    }
    sum.map(|s| s / weights.max(f64::MIN_POSITIVE))
}

/// A ridge regression from features to `[centre x, centre y, radius]`.
struct Localiser {
    weights: DMatrix<f64>,
}

impl Localiser {
    fn train(samples: &[(Vec<f64>, [f64; 3])]) -> Self {
        let n = samples[0].0.len();
        let x = DMatrix::from_fn(samples.len(), n, |i, j| samples[i].0[j]);
        let y = DMatrix::from_fn(samples.len(), 3, |i, j| samples[i].1[j]);
        let mut normal = x.transpose() * &x;
        let ridge = RIDGE * normal.trace() / n as f64;
        for i in 0..n {
            normal[(i, i)] += ridge;
        }
        let weights = normal
            .cholesky()
            .expect("regularised normal equations")
            .solve(&(x.transpose() * y));
        Self { weights }
    }

    fn locate(&self, features: &[f64]) -> [f64; 3] {
        let f = DVector::from_column_slice(features);
        let out = self.weights.transpose() * f;
        [out[0], out[1], out[2]]
    }
}

/// `image` with fresh camera noise of `levels` (standard deviations, R, G, B) drawn from `seed`.
fn with_camera_noise(mut image: RgbImage, levels: [f64; 3], seed: u64) -> RgbImage {
    CameraNoise::new(levels, image.as_raw().len(), seed).add(&mut image);
    image
}

/// The root mean square of `values`.
fn root_mean_square(values: impl ExactSizeIterator<Item = f64>) -> f64 {
    let n = values.len() as f64;
    (values.map(|v| v * v).sum::<f64>() / n).sqrt()
}

/// The median and the largest of `values`.
fn median_and_largest(mut values: Vec<f64>) -> (f64, f64) {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    ((values[(n - 1) / 2] + values[n / 2]) / 2.0, values[n - 1])
}

/// The localiser's errors on the real presses: centre distance and radius difference, pixels.
fn errors(located: &[[f64; 3]], presses: &[Press]) -> ([f64; 2], [f64; 2]) {
    let centre: Vec<f64> = located
        .iter()
        .zip(presses)
        .map(|(l, p)| (l[0] - p.centre[0]).hypot(l[1] - p.centre[1]))
        .collect();
    let radius: Vec<f64> = located
        .iter()
        .zip(presses)
        .map(|(l, p)| (l[2] - p.radius).abs())
        .collect();
    let (c, r) = (median_and_largest(centre), median_and_largest(radius));
    ([c.0, c.1], [r.0, r.1])
}

fn report(name: &str, (centre, radius): ([f64; 2], [f64; 2])) {
    println!(
        "  {name:<44} centre {:>5.1} px median, {:>5.1} largest; radius {:>4.1} median, {:>4.1} largest",
        centre[0], centre[1], radius[0], radius[1]
    );
}

fn main() {
    let folder = format!(
        "{}/yarok-components/data/tactile-real/digit",
        env!("CARGO_MANIFEST_DIR")
    );
    let (names, real): (Vec<String>, Vec<Press>) = read_presses(&format!("{folder}/presses.csv"))
        .expect("the presses")
        .into_iter()
        .unzip();
    let calibration = Calibration::digit();
    let untouched = calibration.background();
    let geometry = calibration.geometry();
    let (width, height) = untouched.dimensions();
    let mut generator = Generator(0x10ca_1153);
    let mut unit = move || generator.next_u64() as f64 / u64::MAX as f64;
    let random_presses: Vec<[f64; 3]> = (0..TRAINING)
        .map(|_| {
            [
                40.0 + unit() * f64::from(width - 80),
                40.0 + unit() * f64::from(height - 80),
                20.0 + unit() * 45.0,
            ]
        })
        .collect();
    let above = |centroid: [f64; 2], press: &Press| press.centre[1] - centroid[1];
    let real_above: Vec<f64> = real
        .iter()
        .map(|press| above(change_centroid(&press.frame, untouched), press))
        .collect();
    let yarok_off: Vec<f64> = real
        .iter()
        .map(|press| {
            let image = calibration.render_press(press.centre, press.radius);
            let [x, y] = change_centroid(&image, untouched);
            (x - press.centre[0]).hypot(y - press.centre[1])
        })
        .collect();
    let real_features: Vec<Vec<f64>> = real
        .iter()
        .map(|press| features(&press.frame, untouched))
        .collect();
    println!(
        "a contact localiser (ridge regression on {BLOCK}×{BLOCK}-pixel change blocks) tested on \
         the real DIGIT's {} presses:",
        real.len()
    );

    let (real_median, real_most) = median_and_largest(real_above.clone());
    let (yarok_median, yarok_most) = median_and_largest(yarok_off);
    println!(
        "  where the change lies (its weighted centroid): real frames {real_median:.1} px above \
         the labelled centre, median ({real_most:.1} largest; {} of {} above); yarok's image of \
         the same press {yarok_median:.1} px from it ({yarok_most:.1} largest)",
        real_above.iter().filter(|a| **a > 0.0).count(),
        real.len()
    );
    let shifts: Vec<[f64; 2]> = real
        .iter()
        .map(|press| calibration.best_move(press))
        .collect();
    let moves: Vec<([f64; 2], [f64; 2])> = real
        .iter()
        .zip(&shifts)
        .map(|(press, shift)| (press.centre, *shift))
        .collect();
    let (size_x, size_y) = (width as usize, height as usize);
    let left_over = Placement::fit(&moves, size_x, size_y);
    let about_line = root_mean_square(moves.iter().map(|(centre, shift)| {
        shift[0] - (left_over.place(*centre, size_x, size_y)[0] - centre[0])
    }));
    let unexplained = root_mean_square(moves.iter().map(|(_, shift)| shift[0]));
    let (up, _) = median_and_largest(shifts.iter().map(|shift| -shift[1]).collect());
    let placement = geometry.placement;
    println!(
        "  where yarok's image of a real press matches the frame best (least contact MAE), beyond \
         the calibration's placement (imprints {:+.1} px across, {:+.1} px down, {:+.1} % further \
         from the middle column): moved across by {:+.1} px + {:.3} × (column − {}) ({about_line:.1} \
         px rms about that line, {unexplained:.1} about none) and up by {up:.1} px (median)",
        placement.shift[0],
        placement.shift[1],
        100.0 * placement.stretch[0],
        left_over.shift[0],
        left_over.stretch[0],
        width / 2
    );
    let yarok: Vec<(Vec<f64>, [f64; 3])> = random_presses
        .iter()
        .zip(0..)
        .map(|(&[x, y, r], seed)| {
            let image = with_camera_noise(
                calibration.render_press([x, y], r),
                calibration.noise_levels(),
                seed,
            );
            (features(&image, untouched), [x, y, r])
        })
        .collect();
    let localiser = Localiser::train(&yarok);
    let located: Vec<[f64; 3]> = real_features.iter().map(|f| localiser.locate(f)).collect();
    report(
        &format!("trained on {TRAINING} yarok calibrated images"),
        errors(&located, &real),
    );
    let (held_located, held_real): (Vec<[f64; 3]>, Vec<Press>) = located
        .iter()
        .zip(&real)
        .zip(&names)
        .filter(|(_, name)| held_out(name, HOLD_OUT))
        .map(|((located, press), _)| (*located, press.clone()))
        .unzip();
    report(
        &format!(
            "  of which the {} held out from the calibration",
            held_real.len()
        ),
        errors(&held_located, &held_real),
    );

    let mut phong = PhongModel::new(PhongParams::digit_metric());
    let surface = 0.030;
    let flat = fidelity::phong_image(&mut phong, surface, &geometry, None, untouched);
    let phong_samples: Vec<(Vec<f64>, [f64; 3])> = random_presses
        .iter()
        .zip(TRAINING as u64..)
        .map(|(&[x, y, r], seed)| {
            let press = Press {
                frame: RgbImage::new(1, 1),
                centre: [x, y],
                radius: r,
            };
            let image = with_camera_noise(
                fidelity::phong_image(&mut phong, surface, &geometry, Some(&press), untouched),
                calibration.noise_levels(),
                seed,
            );
            (features(&image, &flat), [x, y, r])
        })
        .collect();
    let localiser = Localiser::train(&phong_samples);
    let located: Vec<[f64; 3]> = real_features.iter().map(|f| localiser.locate(f)).collect();
    report(
        &format!("trained on {TRAINING} reference Phong images"),
        errors(&located, &real),
    );

    let located: Vec<[f64; 3]> = (0..real.len())
        .map(|left_out| {
            let others: Vec<(Vec<f64>, [f64; 3])> = real
                .iter()
                .zip(&real_features)
                .enumerate()
                .filter(|(i, _)| *i != left_out)
                .map(|(_, (press, f))| {
                    (f.clone(), [press.centre[0], press.centre[1], press.radius])
                })
                .collect();
            Localiser::train(&others).locate(&real_features[left_out])
        })
        .collect();
    report(
        &format!("trained on the other {} real frames", real.len() - 1),
        errors(&located, &real),
    );
}
