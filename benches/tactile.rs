//! Measures, side by side in one run, ms per frame of the tactile optical models on the golden
//! contact cases: DIGIT 320×240 (target ≤ 2 ms), GelSight 640×480 (≤ 8 ms), GelTip 320×240
//! (≤ 4 ms), single-threaded.
//!
//! ```text
//! cargo bench --bench tactile            # every model
//! cargo bench --bench tactile -- gelsight # the models whose name contains `gelsight`
//! ```

use std::path::PathBuf;

use yarok::components::tactile::geltip::{GelTipModel, GelTipParams};
use yarok::components::tactile::npy;
use yarok::components::tactile::phong::{PhongModel, PhongParams};

mod measure;

fn golden(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/golden/tactile")
        .join(path)
}

fn background(model: &str) -> Vec<u8> {
    image::open(golden(&format!("{model}/background.png")))
        .expect("background")
        .to_rgb8()
        .into_raw()
}

fn depth(model: &str) -> npy::NpyArray {
    npy::read(golden(&format!("{model}/sphere_center/input_depth.npy.gz"))).expect("depth")
}

fn main() {
    let filter = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .unwrap_or_default()
        .to_lowercase();
    let selected = |name: &str| name.to_lowercase().contains(&filter);
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    println!("{:<22} {:>10} {:>10}", "model", "ms/frame", "target");
    for (name, model, params, target) in [
        (
            "DIGIT 320×240",
            "digit",
            PhongParams {
                texture_sigma: 0.0,
                ..PhongParams::digit()
            },
            2.0,
        ),
        (
            "GelSight 640×480",
            "gelsight",
            PhongParams {
                texture_sigma: 0.0,
                ..PhongParams::gelsight2014()
            },
            8.0,
        ),
    ] {
        if !selected(name) {
            continue;
        }
        let mut phong = PhongModel::new(params);
        let (input, bg) = (depth(model), background(model));
        let width = input.shape[1];
        let time = measure::mean_time(|| {
            std::hint::black_box(phong.render(&input.data, width, &bg));
        });
        println!("{name:<22} {:>10.2} {target:>10.1}", ms(time));
    }
    if !selected("GelTip") {
        return;
    }
    let mut geltip = GelTipModel::load(GelTipParams::default(), golden("geltip/params"))
        .expect("GelTip geometry");
    let (input, bg) = (depth("geltip"), background("geltip"));
    let time = measure::mean_time(|| {
        std::hint::black_box(geltip.render(&input.data, &bg));
    });
    println!("{:<22} {:>10.2} {:>10.1}", "GelTip 320×240", ms(time), 4.0);
}
