//! Fidelity and speed of the tactile optical models against a real sensor's photographs: for
//! each real set bundled in `yarok-components/data/tactile-real/` (a DIGIT and a GelSight-type
//! sensor from FOTS, ball presses), the median over the held-out presses (frame numbers one less
//! than a multiple of 3, never used to calibrate) of whole-image and contact-region SSIM, MAE and
//! PSNR and of the change-image correlation, for the real untouched frame alone, the reference
//! Phong model (given the real untouched frame) and the calibrated model (the DIGIT's bundled
//! calibration; the GelSight's fitted here to the other presses); then, for the calibrated
//! model, what those medians hide: the change correlation by where on the gel the held-out
//! press is (centre, edge bands, corners: the gel cut in thirds), how the image changes with
//! depth (pairs of real presses within 6 px of each other whose radii differ by 1.5 px or more:
//! the correlation of the simulated difference with the real one), how evenly a flat press
//! (0.856 mm, a grasped block's face) changes the image (the largest change over the median),
//! and the whole-image SSIM as a share of the data's own ceiling (real frames of presses within
//! 5 px and 1.5 px of radius of each other, one smoothed by a Gaussian of σ 1 px as a simulated
//! image has no camera noise, scored against each other); then ms per frame of the
//! calibrated and the reference model, alternating, one core.
//!
//! ```text
//! cargo bench --bench tactile_fidelity
//! ```

use image::RgbImage;
use yarok::components::tactile::calibration::{
    Calibration, FitSettings, Press, RenderBuffers, read_presses, split_held_out,
};
use yarok::components::tactile::fidelity::{self, Scores};
use yarok::components::tactile::phong::{PhongModel, PhongParams};

mod measure;

/// Every 3rd press (0002, 0005, …) is held out of calibration.
const HOLD_OUT: u32 = 3;

struct RealSet {
    name: &'static str,
    untouched: RgbImage,
    calibration: Vec<Press>,
    held_out: Vec<Press>,
}

fn real_set(name: &'static str, presses: &str) -> RealSet {
    let folder = format!(
        "{}/yarok-components/data/tactile-real/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    let untouched = image::open(format!("{folder}/background.png"))
        .expect("untouched frame")
        .to_rgb8();
    let (calibration, held_out) = split_held_out(
        read_presses(&format!("{folder}/{presses}")).expect("presses"),
        HOLD_OUT,
    );
    RealSet {
        name,
        untouched,
        calibration,
        held_out,
    }
}

fn row(model: &str, scores: &Scores) {
    println!(
        "  {model:<22} {:>6.3} {:>8.3} {:>6.2} {:>8.2} {:>6.2} {:>8.2}   {:.2}/{:.2}/{:.2} ({:.2})",
        scores.whole_ssim,
        scores.contact_ssim,
        scores.whole_mae,
        scores.contact_mae,
        scores.whole_psnr,
        scores.contact_psnr,
        scores.change_correlation[0],
        scores.change_correlation[1],
        scores.change_correlation[2],
        scores.mean_change_correlation(),
    );
}

fn main() {
    let sets = [
        (
            real_set("digit", "presses.csv"),
            PhongParams::digit_metric(),
            0.030,
        ),
        (
            real_set("gelsight", "labels.csv"),
            PhongParams::gelsight2014(),
            0.034,
        ),
    ];
    for (set, params, surface) in sets {
        let calibration = if set.name == "digit" {
            Calibration::digit()
        } else {
            let settings = FitSettings::with_geometry(&Calibration::digit().geometry());
            Calibration::fit(&set.untouched, &set.calibration, &settings).expect("a calibration")
        };
        let geometry = calibration.geometry();
        let mut reference = PhongModel::new(params);
        println!(
            "{}: {} held-out presses (calibrated on {}); medians",
            set.name,
            set.held_out.len(),
            set.calibration.len()
        );
        println!(
            "  {:<22} {:>6} {:>8} {:>6} {:>8} {:>6} {:>8}   change correlation R/G/B (mean)",
            "model", "SSIM", "contact", "MAE", "contact", "PSNR", "contact"
        );
        let untouched = &set.untouched;
        let alone = fidelity::score(untouched, untouched, &set.held_out, |_| untouched.clone());
        row("untouched frame alone", &fidelity::median(&alone));
        let flat = fidelity::phong_image(&mut reference, surface, &geometry, None, untouched);
        let phong = fidelity::score(untouched, &flat, &set.held_out, |press| {
            fidelity::phong_image(&mut reference, surface, &geometry, Some(press), untouched)
        });
        row("reference (Phong)", &fidelity::median(&phong));
        let calibrated = fidelity::score(
            untouched,
            calibration.background(),
            &set.held_out,
            |press| calibration.render_press(press.centre, press.radius),
        );
        row("calibrated", &fidelity::median(&calibrated));
        let all: Vec<&Press> = set.calibration.iter().chain(&set.held_out).collect();
        hidden_by_the_medians(&calibration, &set, &all, &calibrated);
        // Each model given its input ready (the press's indentation, or its depth map) and its
        // buffers, as a sensor in the world renders its frames.
        let (width, height) = calibration.size();
        let press = Some(&set.held_out[0]);
        let depth = fidelity::phong_depth(surface, &geometry, press, width, height);
        let indentation: Vec<f32> = depth.iter().map(|d| surface as f32 - d).collect();
        let metres_per_pixel = 1e-3 / geometry.pixels_per_mm;
        let mut buffers = RenderBuffers::default();
        let mut out = vec![0; width * height * 3];
        let [calibrated_ms, reference_ms] = measure::mean_times(|variant| match variant {
            0 => calibration
                .render_indentation_into(&indentation, metres_per_pixel, &mut buffers, &mut out)
                .expect("its size"),
            _ => reference
                .render_into(&depth, width, untouched.as_raw(), &mut out)
                .expect("its size"),
        })
        .map(|t| t.as_secs_f64() * 1e3);
        println!(
            "  ms per frame, one core: calibrated {calibrated_ms:.2}, reference {reference_ms:.2} \
             (calibrated/reference {:.2})",
            calibrated_ms / reference_ms
        );
    }
}

/// The band of the gel a press's centre is in, the gel cut in thirds each way.
fn band(press: &Press, width: u32, height: u32) -> &'static str {
    let third = |at: f64, size: u32| (3.0 * at / f64::from(size)).clamp(0.0, 2.0) as u32;
    match (
        third(press.centre[0], width),
        third(press.centre[1], height),
    ) {
        (1, 1) => "centre",
        (0 | 2, 0 | 2) => "corners",
        _ => "edge bands",
    }
}

/// Pearson correlation of `a` and `b` (0 where either is constant).
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().max(1) as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        ab += (x - ma) * (y - mb);
        aa += (x - ma).powi(2);
        bb += (y - mb).powi(2);
    }
    if aa > 0.0 && bb > 0.0 {
        ab / (aa * bb).sqrt()
    } else {
        0.0
    }
}

/// `a − b` over the pixels within `radius` of `centre`, every channel.
fn difference(a: &RgbImage, b: &RgbImage, centre: [f64; 2], radius: f64) -> Vec<f64> {
    a.enumerate_pixels()
        .filter(|(x, y, _)| {
            let (dx, dy) = (
                f64::from(*x) + 0.5 - centre[0],
                f64::from(*y) + 0.5 - centre[1],
            );
            dx * dx + dy * dy < radius * radius
        })
        .flat_map(|(x, y, p)| {
            let q = b.get_pixel(x, y);
            (0..3).map(move |c| f64::from(p[c]) - f64::from(q[c]))
        })
        .collect()
}

fn median_of(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    (n > 0).then(|| (values[(n - 1) / 2] + values[n / 2]) / 2.0)
}

/// Prints what the held-out medians hide (see the module's documentation).
fn hidden_by_the_medians(
    calibration: &Calibration,
    set: &RealSet,
    all: &[&Press],
    held_out_scores: &[Scores],
) {
    let (width, height) = set.untouched.dimensions();
    let mut bands = Vec::new();
    for name in ["centre", "edge bands", "corners"] {
        let in_band: Vec<f64> = set
            .held_out
            .iter()
            .zip(held_out_scores)
            .filter(|(press, _)| band(press, width, height) == name)
            .map(|(_, scores)| scores.mean_change_correlation())
            .collect();
        match median_of(in_band.clone()) {
            Some(median) => bands.push(format!("{name} {median:.2} ({})", in_band.len())),
            None => bands.push(format!("{name} — (0)")),
        }
    }
    println!(
        "  change correlation by band (held-out presses): {}",
        bands.join(", ")
    );

    let near = |a: &Press, b: &Press| (a.centre[0] - b.centre[0]).hypot(a.centre[1] - b.centre[1]);
    let pairs = |within: f64, radii: &dyn Fn(f64) -> bool| -> Vec<(&Press, &Press)> {
        let mut found = Vec::new();
        for (i, a) in all.iter().enumerate() {
            for b in &all[i + 1..] {
                if near(a, b) <= within && radii((a.radius - b.radius).abs()) {
                    found.push((*a, *b));
                }
            }
        }
        found
    };
    let deeper = pairs(6.0, &|dr| dr >= 1.5);
    let sensitivity: Vec<f64> = deeper
        .iter()
        .map(|(a, b)| {
            let radius = 1.5 * a.radius.max(b.radius);
            let real = difference(&a.frame, &b.frame, a.centre, radius);
            let simulated = difference(
                &calibration.render_press(a.centre, a.radius),
                &calibration.render_press(b.centre, b.radius),
                a.centre,
                radius,
            );
            correlation(&real, &simulated)
        })
        .collect();
    match median_of(sensitivity) {
        Some(median) => println!(
            "  depth sensitivity: {median:.2} median correlation of the simulated and real \
             differences over {} pairs of presses",
            deeper.len()
        ),
        None => println!("  depth sensitivity: no pair of presses within 6 px differs in radius"),
    }

    let metres_per_pixel = 1e-3 / calibration.geometry().pixels_per_mm;
    let (w, h) = calibration.size();
    let flat = calibration
        .render_indentation(&vec![0.856e-3; w * h], metres_per_pixel)
        .expect("its size");
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
    let median = median_of(changes).unwrap_or(0.0);
    println!(
        "  flat press 0.856 mm: median change {median:.0} levels, largest {largest:.0} ({:.1} × \
         the median; even is at most 2)",
        largest / median.max(1.0)
    );

    let same_spot = pairs(5.0, &|dr| dr <= 1.5);
    let ceiling: Vec<f64> = same_spot
        .iter()
        .map(|(a, b)| {
            let disc = fidelity::Disc {
                centre: a.centre,
                radius: 1.5 * a.radius,
            };
            // Smoothed, as a simulated image has no camera noise.
            let smoothed = image::imageops::blur(&b.frame, 1.0);
            fidelity::compare(&a.frame, &set.untouched, &smoothed, &set.untouched, disc).whole_ssim
        })
        .collect();
    let whole = fidelity::median(held_out_scores).whole_ssim;
    match median_of(ceiling) {
        Some(ceiling) => println!(
            "  whole-image SSIM {whole:.3} is {:.0} % of the data's ceiling {ceiling:.3} (median \
             of {} pairs of real frames of one spot)",
            100.0 * whole / ceiling,
            same_spot.len()
        ),
        None => println!("  whole-image SSIM ceiling: no two real presses of one spot"),
    }
}
