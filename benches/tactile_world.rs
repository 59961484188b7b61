//! Measures, side by side in one run, tactile sensors in the world: per sensor, ms per frame
//! (a platform tick that makes a frame, less one that does not) split into the depth render (the
//! sensor's camera alone, fast preset, its own geoms hidden) and the rest (the optical model);
//! and `DigitWorld` with both DIGITs at 60 Hz as a real-time factor. Targets (on a 2-core
//! machine): a DIGIT frame ≤ 3 ms; DigitWorld ≥ 2× real time.
//!
//! ```text
//! cargo bench --bench tactile_world
//! ```

use std::sync::Arc;
use std::time::Instant;

use yarok::components::tactile_sensors::{Digit, GelSight2014, GelTip};
use yarok::components::worlds::{DigitWorld, EmptyWorld};
use yarok::core::component::ComponentType;
use yarok::core::compose::compose_configured;
use yarok::core::config::RunConfig;
use yarok::mjc::{Data, DepthImage, Model, RenderPreset, Renderer};
use yarok::{Component, Declaration};

/// Ticks each platform measurement runs.
const TICKS: u64 = 400;

/// A sensor of tag `T` facing up at z = 0.1 m with a 5 mm sphere pressed 1 mm into its gel
/// (whose outer face is `face` above the camera), making a frame every tick (`fps` 500 at 2 ms)
/// or once (`fps` tiny).
struct Pressed<S>(std::marker::PhantomData<S>);

impl<S: Component> Component for Pressed<S> {
    fn declaration() -> Declaration {
        let tag = S::declaration().tag().to_owned();
        Declaration::new(format!("{tag}_pressed"))
            .extends::<EmptyWorld>()
            .uses::<S>()
            .default("fps", 500.0)
            .default("face", 0.018)
            .template(format!(
                r#"<mujoco><worldbody>
                  <{tag} name="sensor" pos="{{[0, 0, 0.1]}}" fps="{{fps}}"/>
                  <geom type="sphere" size="0.005" pos="{{[0.002, 0.001, 0.1 + face - 0.001 + 0.005]}}"
                        contype="0" conaffinity="0"/>
                </worldbody></mujoco>"#
            ))
    }
}

/// Seconds per tick of a platform on world `W` set up as `settings` say.
fn seconds_per_tick<W: Component>(settings: &[&str]) -> f64 {
    let elapsed = std::rc::Rc::new(std::cell::Cell::new(0.0));
    let out = std::rc::Rc::clone(&elapsed);
    let mut builder = yarok::platform().world::<W>();
    for setting in settings {
        builder = builder.set(setting).expect("setting");
    }
    builder
        .behaviour(move |pl| async move {
            pl.tick().await?;
            let started = Instant::now();
            pl.wait(|| pl.ticks() > TICKS).await?;
            out.set(started.elapsed().as_secs_f64() / TICKS as f64);
            Ok(())
        })
        .run()
        .expect("run");
    elapsed.get()
}

/// Seconds per depth render of the sensor's camera in world `W`, as the sensor renders it: only
/// geoms within `reach` (the farthest point of its gel from its camera).
fn render_seconds<W: Component>(setting: &str, width: u32, height: u32, reach: f64) -> f64 {
    let mut config = RunConfig::default();
    config.set(setting).expect("setting");
    let composition =
        compose_configured(ComponentType::of::<W>(), &config.settings("sim")).expect("compose");
    let model = Arc::new(Model::from_composition(&composition).expect("compile"));
    let mut data = Data::new(&model).expect("data");
    data.forward();
    let camera = model.camera("sensor/camera").expect("camera");
    let mut renderer = Renderer::builder()
        .size(width, height)
        .preset(RenderPreset::Fast)
        .build(&model)
        .expect("renderer");
    renderer.set_visible_groups([true, true, true, false, true, true]);
    renderer.set_reach(Some(reach));
    let mut depth = DepthImage::new(width, height);
    renderer
        .render_depth_into(&mut data, camera, &mut depth)
        .expect("render");
    let started = Instant::now();
    let renders = 100;
    for _ in 0..renders {
        renderer
            .render_depth_into(&mut data, camera, &mut depth)
            .expect("render");
    }
    started.elapsed().as_secs_f64() / f64::from(renders)
}

/// Times a frame of sensor `S` (image `size`, gel face `face` from its camera, `reach`).
fn sensor<S: Component>(name: &str, (width, height): (u32, u32), face: f64, reach: f64) {
    let face = format!("face={face}");
    let framing = seconds_per_tick::<Pressed<S>>(&[&face]);
    let plain = seconds_per_tick::<Pressed<S>>(&[&face, "fps=0.000001"]);
    let frame = (framing - plain).max(0.0);
    let render = render_seconds::<Pressed<S>>(&face, width, height, reach);
    println!(
        "{name:<14} {:>8.2} ms a frame = {:>6.2} render + {:>6.2} model ({width} × {height})",
        frame * 1e3,
        render * 1e3,
        (frame - render).max(0.0) * 1e3
    );
}

fn main() {
    println!("per frame, each sensor pressed by a sphere, frames every 2 ms tick\n");
    sensor::<Digit>("DIGIT", (240, 320), 0.018, 0.022);
    sensor::<GelSight2014>("GelSight 2014", (640, 480), 0.034, 0.041);
    sensor::<GelTip>("GelTip", (320, 240), 0.045, 0.048);
    let per_tick = seconds_per_tick::<DigitWorld>(&[]);
    let timestep = 0.002;
    println!(
        "\nDigitWorld, two DIGITs at 60 Hz, arm holding: {:.2}× real time ({:.3} ms a tick)",
        timestep / per_tick,
        per_tick * 1e3
    );
    println!("\ntargets: a DIGIT frame ≤ 3 ms; DigitWorld ≥ 2× real time");
}
