//! Boxes fall on a plane beside a two-link arm driven by position actuators.
//!
//! The scene is stepped for two simulated seconds while the arm moves to a target pose; then one
//! RGB and one depth image are rendered from the `overview` camera and written as PNG (depth as
//! 16-bit millimetres), and the stepping speed is printed.
//!
//! ```text
//! cargo run --release --example falling_boxes [OUTPUT_DIR]
//! ```

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::Context;
use yarok::mjc::{Data, Model, RenderPreset, Renderer, depth_to_millimetres};

const SCENE: &str = include_str!("falling_boxes.xml");
const SIMULATED_SECONDS: f64 = 2.0;
const BOXES: [&str; 4] = ["box_red", "box_green", "box_blue", "box_yellow"];

fn main() -> anyhow::Result<()> {
    tracing_subscriber::fmt()
        .with_env_filter(tracing_subscriber::EnvFilter::from_default_env())
        .init();
    let out_dir = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from("out"), PathBuf::from);
    std::fs::create_dir_all(&out_dir).with_context(|| format!("creating {}", out_dir.display()))?;

    let model = Arc::new(Model::from_xml_str(SCENE)?);
    let mut data = Data::new(&model)?;
    data.set_ctrl(model.actuator("shoulder")?, 0.8);
    data.set_ctrl(model.actuator("elbow")?, -1.2);

    let steps = (SIMULATED_SECONDS / model.timestep()).round() as u32;
    let started = Instant::now();
    for _ in 0..steps {
        data.step();
    }
    let elapsed = started.elapsed().as_secs_f64();
    println!(
        "stepped {steps} steps ({SIMULATED_SECONDS} s simulated) in {:.1} ms: {:.0} steps/s, {:.0}x real time",
        elapsed * 1e3,
        f64::from(steps) / elapsed,
        SIMULATED_SECONDS / elapsed
    );
    for name in BOXES {
        let pose = data.body_pose(model.body(name)?);
        println!("{name:>10} rests at z = {:.3} m", pose.pos[2]);
    }
    println!(
        "elbow at {:.3} rad (target -1.2), forearm origin at {:.3?} m",
        data.sensor(model.sensor("elbow_angle")?)[0],
        data.sensor(model.sensor("forearm_pos")?)
    );

    let mut renderer = Renderer::builder()
        .size(640, 480)
        .preset(RenderPreset::Quality)
        .build(&model)?;
    let (rgb, depth) = renderer.render(&mut data, model.camera("overview")?)?;
    let rgb_path = out_dir.join("falling_boxes_rgb.png");
    let depth_path = out_dir.join("falling_boxes_depth_mm.png");
    rgb.save(&rgb_path)
        .with_context(|| format!("writing {}", rgb_path.display()))?;
    depth_to_millimetres(&depth)
        .save(&depth_path)
        .with_context(|| format!("writing {}", depth_path.display()))?;
    println!("wrote {} and {}", rgb_path.display(), depth_path.display());
    Ok(())
}
