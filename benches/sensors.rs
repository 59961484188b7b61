//! Measures, side by side in one run, sensors in the world. Cameras: a `Cam` of 640×480 looking
//! at a tumble tower, frames a second for colour, for colour and depth from one draw
//! (`read_rgbd`) and from two, in the quality and fast presets; the start-up of a renderer (OpenGL
//! context, MuJoCo's render context with the world's textures, first frame) in each preset.
//! Tactile sensors: per sensor, ms per frame
//! (a platform tick that makes a frame, less one that does not) split into the depth render (the
//! sensor's camera alone, depth preset, its own geoms hidden) and the rest (the optical model);
//! the DIGIT with its bundled calibration and with the reference Phong model, on the platform's
//! thread, in alternating rounds; `DigitWorld` with both DIGITs at 60 Hz as a real-time factor;
//! and the samples a second of one and of two `TactileRigWorld`s on threads of their own, with
//! llvmpipe's rasteriser threads and without (`LP_NUM_THREADS=0`, measured in a child process),
//! in alternating rounds with each side's fastest reported. Targets (on a 2-core machine): the
//! calibrated DIGIT's frame and model no slower than the reference's; DigitWorld ≥ 5× real time;
//! 2 rigs ≥ 1.7× one.
//!
//! ```text
//! cargo bench --bench sensors
//! ```

use std::cell::Cell;
use std::rc::Rc;
use std::sync::{Arc, Barrier};
use std::time::Instant;

use yarok::components::cameras::Cam;
use yarok::components::tactile_sensors::{Digit, GelSight2014, GelTip};
use yarok::components::worlds::{DigitWorld, EmptyWorld, Press, TactileRigWorld, TowerWorld};
use yarok::core::component::ComponentType;
use yarok::core::compose::{compose, compose_configured};
use yarok::core::config::RunConfig;
use yarok::mjc::{Data, DepthImage, Model, RenderPreset, Renderer};
use yarok::{Component, Declaration};

mod measure;

/// Rounds of each measurement, of which the fastest counts (the least disturbed by the rest of
/// the machine), and ticks or renders a round.
const ROUNDS: usize = 5;
const TICKS: u64 = 100;
const RENDERS: u32 = 30;

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
                  <geom type="sphere" size="0.005" pos="{{[0.002, 0.001, 0.1 + face - 0.001 + 0.005]}}"/>
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
            let mut fastest = f64::INFINITY;
            for _ in 0..ROUNDS {
                let (started, until) = (Instant::now(), pl.ticks() + TICKS);
                pl.wait(|| pl.ticks() >= until).await?;
                fastest = fastest.min(started.elapsed().as_secs_f64() / TICKS as f64);
            }
            out.set(fastest);
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
        .preset(RenderPreset::Depth)
        .build(&model)
        .expect("renderer");
    renderer.set_visible_groups([true, true, true, false, true, true]);
    renderer.set_reach(Some(reach));
    let mut depth = DepthImage::new(width, height);
    renderer
        .render_depth_into(&mut data, camera, &mut depth)
        .expect("render");
    let mut fastest = f64::INFINITY;
    for _ in 0..ROUNDS {
        let started = Instant::now();
        for _ in 0..RENDERS {
            renderer
                .render_depth_into(&mut data, camera, &mut depth)
                .expect("render");
        }
        fastest = fastest.min(started.elapsed().as_secs_f64() / f64::from(RENDERS));
    }
    fastest
}

/// Seconds a frame of sensor `S` in world `Pressed<S>` set up as `settings` say (plus its gel
/// face `face`) takes in all and in its depth render (image `size`, `reach`).
fn frame_seconds<S: Component>(
    settings: &[&str],
    (width, height): (u32, u32),
    face: f64,
    reach: f64,
) -> (f64, f64) {
    let face = format!("face={face}");
    let mut framing = vec![face.as_str(), "fps=500"];
    framing.extend(settings);
    let mut plain = vec![face.as_str(), "fps=0.000001"];
    plain.extend(settings);
    let framing = seconds_per_tick::<Pressed<S>>(&framing);
    let plain = seconds_per_tick::<Pressed<S>>(&plain);
    let render = render_seconds::<Pressed<S>>(&face, width, height, reach);
    ((framing - plain).max(0.0), render)
}

fn print_frame(name: &str, (frame, render): (f64, f64), (width, height): (u32, u32)) {
    println!(
        "{name:<24} {:>6.2} ms a frame = {:>6.2} render + {:>6.2} model ({width} × {height})",
        frame * 1e3,
        render * 1e3,
        (frame - render).max(0.0) * 1e3
    );
}

/// Times a frame of sensor `S` (image `size`, gel face `face` from its camera, `reach`).
fn sensor<S: Component>(name: &str, size: (u32, u32), face: f64, reach: f64) {
    print_frame(name, frame_seconds::<S>(&[], size, face, reach), size);
}

/// Rounds of the DIGIT's calibrated and reference models in the world, taking turns.
const MODEL_ROUNDS: usize = 3;

/// A DIGIT frame in the world with its bundled calibration and with the reference Phong model,
/// in alternating rounds (each side's fastest counts), the model on the platform's thread.
fn digit_models() {
    let size = (240, 320);
    let time = |calibration: &str| {
        let setting = format!("/sensor/calibration=\"{calibration}\"");
        frame_seconds::<Digit>(&[&setting, "/sensor/parallel=false"], size, 0.018, 0.022)
    };
    let fastest = |a: (f64, f64), b: (f64, f64)| (a.0.min(b.0), a.1.min(b.1));
    let mut calibrated = (f64::INFINITY, f64::INFINITY);
    let mut reference = calibrated;
    for _ in 0..MODEL_ROUNDS {
        calibrated = fastest(calibrated, time("bundled"));
        reference = fastest(reference, time("none"));
    }
    print_frame("DIGIT calibrated", calibrated, size);
    print_frame("DIGIT reference (Phong)", reference, size);
    let model = |(frame, render): (f64, f64)| (frame - render).max(1e-9);
    println!(
        "  calibrated/reference: frame {:.2}, model {:.2}",
        calibrated.0 / reference.0,
        model(calibrated) / model(reference)
    );
}

/// Samples a second that `rigs` tactile rigs (GelTip, models on one thread each), one per
/// thread, collect together after their start-up: each presses `presses` times around its
/// sensor's axis.
fn rig_throughput(rigs: usize, presses: usize) -> f64 {
    let ready = Arc::new(Barrier::new(rigs));
    let spans = std::thread::scope(|scope| {
        let rigs: Vec<_> = (0..rigs)
            .map(|_| {
                let ready = Arc::clone(&ready);
                scope.spawn(move || {
                    let span = Rc::new(Cell::new(None));
                    let out = Rc::clone(&span);
                    yarok::platform()
                        .world::<TactileRigWorld>()
                        .set("parallel=false")
                        .expect("setting")
                        .behaviour(move |pl| async move {
                            let rig: TactileRigWorld = pl.get("/")?;
                            let press = |i: usize| Press {
                                at: [(i % 5) as f64 * 0.002 - 0.004, 0.0],
                                depth: 0.0005 + (i % 3) as f64 * 0.0005,
                            };
                            rig.press(press(0)).await?;
                            ready.wait();
                            let started = Instant::now();
                            for i in 0..presses {
                                rig.press(press(i)).await?;
                            }
                            out.set(Some((started, Instant::now())));
                            Ok(())
                        })
                        .run()
                        .expect("run");
                    span.get().expect("a span")
                })
            })
            .collect();
        rigs.into_iter()
            .map(|rig| rig.join().expect("a rig"))
            .collect::<Vec<_>>()
    });
    let started = spans.iter().map(|(s, _)| *s).min().expect("a rig");
    let ended = spans.iter().map(|(_, e)| *e).max().expect("a rig");
    (rigs * presses) as f64 / (ended - started).as_secs_f64()
}

/// The tower world with a 640×480 `Cam` 1.5 m away looking at the tower.
struct CameraWorld;

impl Component for CameraWorld {
    fn declaration() -> Declaration {
        Declaration::new("camera_world")
            .extends::<TowerWorld>()
            .uses::<Cam>()
            .default("preset", "quality")
            .template(
                r#"<mujoco><worldbody>
                  <body pos="1.1 -1.1 0.7" xyaxes="0.7071 0.7071 0 -0.2 0.2 0.96">
                    <cam name="cam" preset="{preset}"/>
                  </body>
                </worldbody></mujoco>"#,
            )
    }
}

/// Frames a second of the world's camera in `preset`: colour, colour + depth from one draw, and
/// from two.
fn frames_per_second(preset: &str) -> [f64; 3] {
    let rates = std::rc::Rc::new(std::cell::Cell::new([0.0; 3]));
    let out = std::rc::Rc::clone(&rates);
    yarok::platform()
        .world::<CameraWorld>()
        .set(&format!("preset=\"{preset}\""))
        .expect("setting")
        .behaviour(move |pl| async move {
            let cam: Cam = pl.get("/cam")?;
            let times: [_; 3] = measure::mean_times(|variant| match variant {
                0 => cam.read().map(|_| ()),
                1 => cam.read_rgbd().map(|_| ()),
                _ => cam.read().and_then(|_| cam.read_depth()).map(|_| ()),
            });
            out.set(times.map(|time| 1.0 / time.as_secs_f64()));
            Ok(())
        })
        .run()
        .expect("run");
    rates.get()
}

/// Milliseconds to build a renderer of the world's camera size in `preset` and draw its first
/// frame: the fastest of three.
fn start_up_ms(model: &Arc<Model>, data: &mut Data, preset: RenderPreset) -> f64 {
    let camera = model.camera("cam/camera").expect("camera");
    (0..3)
        .map(|_| {
            let started = Instant::now();
            let mut renderer = Renderer::builder()
                .size(640, 480)
                .preset(preset)
                .build(model)
                .expect("renderer");
            renderer.render_rgb(data, camera).expect("render");
            started.elapsed().as_secs_f64() * 1e3
        })
        .fold(f64::INFINITY, f64::min)
}

/// Prints the cameras' start-up and frame rates.
fn cameras() {
    let model = Arc::new(
        Model::from_composition(&compose::<CameraWorld>().expect("compose")).expect("compile"),
    );
    let mut data = Data::new(&model).expect("data");
    data.forward();
    let started = Instant::now();
    let first = Renderer::builder()
        .size(640, 480)
        .preset(RenderPreset::Fast)
        .build(&model)
        .expect("renderer");
    let first_ms = started.elapsed().as_secs_f64() * 1e3;
    drop(first);
    println!(
        "renderer start-up, build and first frame (ms); the process's first {first_ms:.0} (fast, \
         with EGL's set-up)"
    );
    println!("           alone (its own OpenGL context)   beside another (the thread's context)");
    for (name, preset) in [
        ("quality", RenderPreset::Quality),
        ("fast", RenderPreset::Fast),
        ("depth", RenderPreset::Depth),
    ] {
        let alone = start_up_ms(&model, &mut data, preset);
        let other = Renderer::builder()
            .size(320, 240)
            .preset(RenderPreset::Fast)
            .build(&model)
            .expect("renderer");
        let beside = start_up_ms(&model, &mut data, preset);
        drop(other);
        println!("  {name:<8} {alone:>18.0} {beside:>38.0}");
    }
    println!("\nCam 640×480, frames/s   colour   colour+depth (one draw)   (two draws)");
    for preset in ["quality", "fast"] {
        let [rgb, rgbd, both] = frames_per_second(preset);
        println!("  {preset:<8} {rgb:>19.1} {rgbd:>14.1} {both:>21.1}");
    }
}

/// Rounds of one rig then two, so that machine noise (which only ever slows a round down) hits
/// both alike.
const RIG_ROUNDS: usize = 4;

/// Prints the rigs' throughput with 1 and with 2 rigs, labelled `how`: each side's fastest round,
/// and the median of the rounds' ratios.
fn rigs(how: &str) {
    let presses = 150;
    let rounds: Vec<(f64, f64)> = (0..RIG_ROUNDS)
        .map(|_| (rig_throughput(1, presses), rig_throughput(2, presses)))
        .collect();
    let fastest = |side: fn(&(f64, f64)) -> f64| rounds.iter().map(side).fold(0.0, f64::max);
    let (one, two) = (fastest(|r| r.0), fastest(|r| r.1));
    let mut ratios: Vec<f64> = rounds.iter().map(|(one, two)| two / one).collect();
    ratios.sort_by(f64::total_cmp);
    println!(
        "TactileRigWorld (GelTip), {how}: 1 rig {one:.1} samples/s, 2 rigs on 2 threads {two:.1} \
         ({:.2}×; median of {RIG_ROUNDS} rounds' ratios {:.2}×)",
        two / one,
        ratios[RIG_ROUNDS / 2],
    );
}

fn main() {
    if std::env::args().any(|arg| arg == "--rigs-only") {
        rigs("LP_NUM_THREADS=0 (llvmpipe rasterises on each rig's thread)");
        return;
    }
    cameras();
    println!("\ntactile sensors, per frame, each pressed by a sphere, frames every 2 ms tick\n");
    digit_models();
    sensor::<GelSight2014>("GelSight 2014", (640, 480), 0.034, 0.041);
    sensor::<GelTip>("GelTip", (320, 240), 0.045, 0.048);
    let per_tick = seconds_per_tick::<DigitWorld>(&[]);
    let timestep = 0.002;
    println!(
        "\nDigitWorld, two DIGITs at 60 Hz, arm holding: {:.2}× real time ({:.3} ms a tick)",
        timestep / per_tick,
        per_tick * 1e3
    );
    println!();
    rigs("llvmpipe's own threads");
    // llvmpipe reads its thread count once per process.
    let child = std::process::Command::new(std::env::current_exe().expect("this bench"))
        .arg("--rigs-only")
        .env("LP_NUM_THREADS", "0")
        .output()
        .expect("the bench again");
    print!("{}", String::from_utf8_lossy(&child.stdout));
    println!(
        "\ntargets: a calibrated DIGIT frame, and its model, no slower than the reference's; \
         DigitWorld ≥ 5× real time; 2 rigs ≥ 1.7× one"
    );
}
