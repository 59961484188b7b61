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
use yarok::core::compose::compose;
use yarok::mjc::{Data, Model, RenderPreset, Renderer};
use yarok::{Component, Declaration};

/// Ticks each platform measurement runs.
const TICKS: u64 = 400;

/// A sensor of tag `T` facing up at z = 0.1 m with a sphere pressed into it, making a frame
/// every tick (`fps` 500 at 2 ms) or once (`fps` tiny).
struct Pressed<S>(std::marker::PhantomData<S>);

impl<S: Component> Component for Pressed<S> {
    fn declaration() -> Declaration {
        let tag = S::declaration().tag().to_owned();
        Declaration::new(format!("{tag}_pressed"))
            .extends::<EmptyWorld>()
            .uses::<S>()
            .default("fps", 500.0)
            .template(format!(
                r#"<mujoco><worldbody>
                  <{tag} name="sensor" pos="{{[0, 0, 0.1]}}" fps="{{fps}}"/>
                  <geom type="sphere" size="0.005" pos="0.002 0.001 0.116" contype="0" conaffinity="0"/>
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

/// Seconds per depth render of the sensor's camera in world `W`, as the sensor renders it.
fn render_seconds<W: Component>(width: u32, height: u32) -> f64 {
    let model =
        Arc::new(Model::from_composition(&compose::<W>().expect("compose")).expect("compile"));
    let mut data = Data::new(&model).expect("data");
    data.forward();
    let camera = model.camera("sensor/camera").expect("camera");
    let mut renderer = Renderer::builder()
        .size(width, height)
        .preset(RenderPreset::Fast)
        .build(&model)
        .expect("renderer");
    renderer.set_visible_groups([true, true, true, false, true, true]);
    renderer.render_depth(&mut data, camera).expect("render");
    let started = Instant::now();
    let renders = 100;
    for _ in 0..renders {
        std::hint::black_box(renderer.render_depth(&mut data, camera).expect("render"));
    }
    started.elapsed().as_secs_f64() / f64::from(renders)
}

fn sensor<S: Component>(name: &str, width: u32, height: u32) {
    let framing = seconds_per_tick::<Pressed<S>>(&[]);
    let plain = seconds_per_tick::<Pressed<S>>(&["fps=0.000001"]);
    let frame = (framing - plain).max(0.0);
    let render = render_seconds::<Pressed<S>>(width, height);
    println!(
        "{name:<14} {:>8.2} ms a frame = {:>6.2} render + {:>6.2} model ({width} × {height})",
        frame * 1e3,
        render * 1e3,
        (frame - render).max(0.0) * 1e3
    );
}

fn main() {
    println!("per frame, each sensor pressed by a sphere, frames every 2 ms tick\n");
    sensor::<Digit>("DIGIT", 240, 320);
    sensor::<GelSight2014>("GelSight 2014", 640, 480);
    sensor::<GelTip>("GelTip", 320, 240);
    let per_tick = seconds_per_tick::<DigitWorld>(&[]);
    let timestep = 0.002;
    println!(
        "\nDigitWorld, two DIGITs at 60 Hz, arm holding: {:.2}× real time ({:.3} ms a tick)",
        timestep / per_tick,
        per_tick * 1e3
    );
    println!("\ntargets: a DIGIT frame ≤ 3 ms; DigitWorld ≥ 2× real time");
}
