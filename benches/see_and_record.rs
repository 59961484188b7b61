//! What watching and recording cost, in PickAndPlaceWorld while the arm stacks blocks: ticks per
//! second without a plugin, with the MCAP recorder in its Foxglove and its ROS 2 profile (joint
//! states and poses every 10 ticks; then also the overview camera at 320×240, 10 images a
//! second) and with the LeRobot dataset writer (joint positions and actuator commands 30 frames
//! a second; then also the overview camera at 320×240 as an H.264 video), measured side by side;
//! and, with
//! the viewer's window (800×600, under Xvfb when no display is set) pacing the run to the wall
//! clock, the share of wall time the viewer spends drawing.
//!
//! ```text
//! cargo bench --features viewer,dataset --bench see_and_record
//! ```

use std::cell::Cell;
use std::rc::Rc;
use std::time::{Duration, Instant};

use yarok::components::demos;
use yarok::components::plugins::{
    DatasetRecorder, DatasetRecorderSettings, McapRecorder, McapRecorderSettings, Viewer,
    ViewerSettings,
};
use yarok::components::worlds::PickAndPlaceWorld;
use yarok::{BoxError, Plugin, World};
use yarok_test::XServer;

#[path = "measure.rs"]
mod measure;

use measure::mean_times;

/// Platform seconds each measured run lasts.
const RUN: f64 = 6.0;

/// PickAndPlaceWorld stacking for `seconds`, with `plugin`; the ticks it made.
fn run(seconds: f64, plugin: Option<Box<dyn Plugin>>) -> u64 {
    let ticks = Rc::new(Cell::new(0));
    let counted = Rc::clone(&ticks);
    let mut platform =
        yarok::platform()
            .world::<PickAndPlaceWorld>()
            .behaviour(move |pl| async move {
                let _stacking_cut_short = pl.timeout(seconds, demos::stack(pl.clone())).await;
                counted.set(pl.ticks());
                Ok(())
            });
    if let Some(plugin) = plugin {
        platform = platform.plugin(Boxed(plugin));
    }
    platform.run().expect("the run");
    ticks.get()
}

/// A boxed plugin, as one.
struct Boxed(Box<dyn Plugin>);

impl Plugin for Boxed {
    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.0.start(world)
    }
    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.0.step(world)
    }
    fn end(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.0.end(world)
    }
}

/// A viewer that tells how long it drew once the run ends.
struct MeasuredViewer {
    viewer: Viewer,
    drawing: Rc<Cell<(Duration, u64)>>,
}

impl Plugin for MeasuredViewer {
    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.viewer.start(world)
    }
    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.viewer.step(world)
    }
    fn end(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.drawing.set(self.viewer.drawing());
        self.viewer.end(world)
    }
}

/// An X server for the viewer when none is set.
fn display() -> Option<XServer> {
    if std::env::var_os("DISPLAY").is_some() {
        return None;
    }
    let server = XServer::start();
    // SAFETY: set before any other thread of this process reads the environment.
    unsafe { std::env::set_var("DISPLAY", server.display()) };
    Some(server)
}

fn recorder(folder: &std::path::Path, profile: &str, cameras: Vec<String>) -> Box<dyn Plugin> {
    let settings = McapRecorderSettings {
        path: folder.join("bench.mcap"),
        cameras,
        size: [320, 240],
        profile: profile.to_owned(),
        ..McapRecorderSettings::default()
    };
    Box::new(McapRecorder::new(settings).expect("valid settings"))
}

fn dataset(folder: &std::path::Path, cameras: Vec<String>) -> Box<dyn Plugin> {
    let settings = DatasetRecorderSettings {
        path: folder.join("dataset"),
        cameras,
        size: [320, 240],
        ..DatasetRecorderSettings::default()
    };
    Box::new(DatasetRecorder::new(settings).expect("valid settings"))
}

fn main() {
    let _x_server = display();
    let folder = tempfile::tempdir().unwrap();
    let ticks = run(RUN, None);
    let overview = || vec!["overview".to_owned()];
    let [bare, foxglove, ros2, filmed, lerobot, lerobot_filmed] =
        mean_times(|variant| match variant {
            0 => run(RUN, None),
            1 => run(RUN, Some(recorder(folder.path(), "foxglove", Vec::new()))),
            2 => run(RUN, Some(recorder(folder.path(), "ros2", Vec::new()))),
            3 => run(RUN, Some(recorder(folder.path(), "foxglove", overview()))),
            4 => run(RUN, Some(dataset(folder.path(), Vec::new()))),
            _ => run(RUN, Some(dataset(folder.path(), overview()))),
        });
    let rate = |time: Duration| ticks as f64 / time.as_secs_f64();
    println!("PickAndPlaceWorld stacking, {RUN} s of platform time ({ticks} ticks), side by side:");
    println!(
        "  no plugin                                  {:>8.0} ticks/s",
        rate(bare)
    );
    for (name, time) in [
        ("MCAP recorder, foxglove (joints, poses)   ", foxglove),
        ("MCAP recorder, ros2 (joints, poses, clock)", ros2),
        ("MCAP recorder, foxglove + camera 320×240  ", filmed),
        ("dataset writer (joints, actions, 30 fps)  ", lerobot),
        ("dataset writer + camera 320×240 video     ", lerobot_filmed),
    ] {
        println!(
            "  {name} {:>8.0} ticks/s  ({:.1} % of the bare rate)",
            rate(time),
            100.0 * bare.as_secs_f64() / time.as_secs_f64()
        );
    }

    let drawing = Rc::new(Cell::new((Duration::ZERO, 0)));
    let shared = Rc::clone(&drawing);
    let seconds = 4.0;
    let started = Instant::now();
    run(
        seconds,
        Some(Box::new(MeasuredViewer {
            viewer: Viewer::new(ViewerSettings::default()).expect("valid settings"),
            drawing: shared,
        })),
    );
    let wall = started.elapsed().as_secs_f64();
    let (drawing, frames) = drawing.get();
    let drawing = drawing.as_secs_f64();
    println!(
        "viewer 800×600 at real-time pacing: {seconds} s of platform time in {wall:.2} s of wall \
         time; {frames} frames ({:.1} a second, {:.1} ms each) took {:.1} % of the wall time",
        frames as f64 / wall,
        1e3 * drawing / frames.max(1) as f64,
        100.0 * drawing / wall
    );
}
