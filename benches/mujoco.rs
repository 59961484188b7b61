//! Measures, side by side in one run, MuJoCo stepping and offscreen rendering on the
//! falling-boxes example scene: raw `mj_step` steps/s, and render frames/s at 640×480 and
//! 320×240 in the `quality` and `fast` presets, with the fast/quality ratio.
//!
//! ```text
//! cargo bench --bench mujoco
//! ```

use std::sync::Arc;

use yarok::mjc::{Data, Model, RenderPreset, Renderer};

const SCENE: &str = include_str!("../examples/sim/falling_boxes.xml");
mod measure;

/// Runs per second, from the mean time of one run.
fn rate(time: std::time::Duration) -> f64 {
    1.0 / time.as_secs_f64()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let model = Arc::new(Model::from_xml_str(SCENE)?);
    let mut data = Data::new(&model)?;
    let [step_time] = measure::mean_times(|_| {
        data.step();
        if data.time() > 2.0 {
            data.reset();
        }
        data.time()
    });
    let steps_per_s = rate(step_time);
    println!("mj_step, falling boxes: {steps_per_s:>10.0} steps/s");

    let camera = model.camera("overview")?;
    data.reset();
    for _ in 0..500 {
        data.step();
    }
    println!("\nrender fps     quality       fast  fast/quality");
    for (width, height) in [(640, 480), (320, 240)] {
        let renderer = |preset| {
            Renderer::builder()
                .size(width, height)
                .preset(preset)
                .build(&model)
        };
        let mut renderers = [
            renderer(RenderPreset::Quality)?,
            renderer(RenderPreset::Fast)?,
        ];
        let times: [_; 2] = measure::mean_times(|variant| {
            renderers[variant]
                .render_rgb(&mut data, camera)
                .expect("render")
        });
        let fps = times.map(rate);
        println!(
            "{:<10} {:>11.1} {:>10.1} {:>12.2}x",
            format!("{width}x{height}"),
            fps[0],
            fps[1],
            fps[1] / fps[0]
        );
    }
    Ok(())
}
