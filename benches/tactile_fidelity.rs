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
            // Its own geometry, searched among the default candidates (its presses are contact
            // circles, the DIGIT's visible imprints).
            Calibration::fit(&set.untouched, &set.calibration, &FitSettings::default())
                .expect("a calibration")
        };
        let geometry = calibration.geometry();
        let mut reference = PhongModel::new(params);
        println!(
            "{}: {} held-out presses (calibrated on {}: contact scale {}, spread {} px); medians",
            set.name,
            set.held_out.len(),
            set.calibration.len(),
            geometry.contact_scale,
            geometry.spread
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

/// Prints what the held-out medians hide (see the module's documentation).
fn hidden_by_the_medians(
    calibration: &Calibration,
    set: &RealSet,
    all: &[&Press],
    held_out_scores: &[Scores],
) {
    let (width, height) = set.untouched.dimensions();
    let bands: Vec<String> =
        fidelity::change_correlation_by_band(&set.held_out, held_out_scores, width, height)
            .iter()
            .map(|(band, median, count)| match median {
                Some(median) => format!("{} {median:.2} ({count})", band.name()),
                None => format!("{} — (0)", band.name()),
            })
            .collect();
    println!(
        "  change correlation by band (held-out presses): {}",
        bands.join(", ")
    );
    match fidelity::depth_sensitivity(all, |press| {
        calibration.render_press(press.centre, press.radius)
    }) {
        (Some(median), pairs) => println!(
            "  depth sensitivity: {median:.2} median correlation of the simulated and real \
             differences over {pairs} pairs of presses"
        ),
        (None, _) => {
            println!("  depth sensitivity: no pair of presses within 6 px differs in radius")
        }
    }
    let (largest, median) = fidelity::flat_press_changes(calibration, FLAT_PRESS_M);
    println!(
        "  flat press {} mm: median change {median:.0} levels, largest {largest:.0} ({:.1} × \
         the median; even is at most 2)",
        FLAT_PRESS_M * 1e3,
        largest / median.max(1.0)
    );
    let whole = fidelity::median(held_out_scores).whole_ssim;
    match fidelity::ssim_ceiling(all, &set.untouched) {
        (Some(ceiling), pairs) => println!(
            "  whole-image SSIM {whole:.3} is {:.0} % of the data's ceiling {ceiling:.3} (median \
             of {pairs} pairs of real frames of one spot)",
            100.0 * whole / ceiling,
        ),
        (None, _) => println!("  whole-image SSIM ceiling: no two real presses of one spot"),
    }
}

/// A grasped block's face sinking the gel evenly: what `DigitWorld`'s grasp gives.
const FLAT_PRESS_M: f32 = 0.856e-3;
