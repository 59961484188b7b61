//! Measures, side by side in one run, ms per frame of the tactile optical models on the golden
//! `sphere_center` case, single-threaded and split over rayon's pool: DIGIT 320×240 (target
//! ≤ 2 ms single-threaded), GelSight 640×480 (≤ 8 ms), GelTip 320×240 (≤ 4 ms). Texture noise is
//! on, as sensors run by default.
//!
//! ```text
//! cargo bench --bench tactile             # every model
//! cargo bench --bench tactile -- gelsight # the models whose name contains `gelsight`
//! ```

use std::path::PathBuf;

use yarok::components::tactile::geltip::{GelTipModel, GelTipParams};
use yarok::components::tactile::npy;
use yarok::components::tactile::phong::{PhongModel, PhongParams};

mod measure;

fn golden(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden/tactile")
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

/// Renders one frame with the model split over threads or not.
trait Model {
    fn set_parallel(&mut self, parallel: bool);
    fn render(&mut self) -> Vec<u8>;
}

struct Phong {
    model: PhongModel,
    depth: npy::NpyArray,
    background: Vec<u8>,
}

impl Model for Phong {
    fn set_parallel(&mut self, parallel: bool) {
        self.model.set_parallel(parallel);
    }
    fn render(&mut self) -> Vec<u8> {
        let width = self.depth.shape[1];
        self.model
            .render(&self.depth.data, width, &self.background)
            .expect("golden sizes")
    }
}

struct GelTip {
    model: GelTipModel,
    depth: npy::NpyArray,
    background: Vec<u8>,
}

impl Model for GelTip {
    fn set_parallel(&mut self, parallel: bool) {
        self.model.set_parallel(parallel);
    }
    fn render(&mut self) -> Vec<u8> {
        self.model
            .render(&self.depth.data, &self.background)
            .expect("golden sizes")
    }
}

fn phong(name: &str, params: PhongParams) -> Box<dyn Model> {
    Box::new(Phong {
        model: PhongModel::new(params),
        depth: depth(name),
        background: background(name),
    })
}

fn main() {
    let filter = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .unwrap_or_default()
        .to_lowercase();
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    println!(
        "{:<18} {:>16} {:>12} {:>9} {:>10}   ({} threads)",
        "model",
        "single ms/frame",
        "parallel ms",
        "speed-up",
        "target",
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    type Make = fn() -> Box<dyn Model>;
    let models: [(&str, f64, Make); 3] = [
        ("DIGIT 320×240", 2.0, || {
            phong("digit", PhongParams::digit())
        }),
        ("GelSight 640×480", 8.0, || {
            phong("gelsight", PhongParams::gelsight2014())
        }),
        ("GelTip 320×240", 4.0, || {
            Box::new(GelTip {
                model: GelTipModel::load(GelTipParams::default(), golden("geltip/params"))
                    .expect("GelTip geometry"),
                depth: depth("geltip"),
                background: background("geltip"),
            })
        }),
    ];
    for (name, target, make) in models {
        if !name.to_lowercase().contains(&filter) {
            continue;
        }
        let mut model = make();
        let single_image = model.render();
        model.set_parallel(true);
        assert_eq!(
            model.render(),
            single_image,
            "{name}: threads change the image"
        );
        let [single, parallel] = measure::mean_times(|variant| {
            model.set_parallel(variant == 1);
            model.render()
        });
        println!(
            "{name:<18} {:>16.2} {:>12.2} {:>8.2}× {target:>10.1}",
            ms(single),
            ms(parallel),
            single.as_secs_f64() / parallel.as_secs_f64()
        );
    }
}
