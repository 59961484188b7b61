//! Many worlds per process, side by side in one run: PickAndPlaceWorlds stacking for 2 s of
//! platform time each, 8 of them on 1 and on 2 threads (`run_parallel`) — worlds and ticks per
//! second; the memory an extra world takes with the compiled model shared and with a model of
//! its own; and, for the largest bundled world, its model compiled against loaded from the
//! compiled-model cache, and its whole start-up (built and bound, to its first tick) each way.
//!
//! With the feature `zenoh`, the Zenoh bridge's cost per tick and loopback round trip too
//! (`benches/zenoh_bridge.rs`).
//!
//! ```text
//! cargo bench --features zenoh --bench many_worlds
//! ```

use std::rc::Rc;
use std::sync::Arc;
use std::time::{Duration, Instant};

use yarok::components::demos;
use yarok::components::worlds::{GelTipWorld, PickAndPlaceWorld};
use yarok::core::runtime::{PlatformBuilder, run_parallel};
use yarok::mjc::{Model, ModelSource, Sim, SimBackend};

#[path = "measure.rs"]
mod measure;
#[cfg(feature = "zenoh")]
#[path = "zenoh_bridge.rs"]
mod zenoh_bridge;

use measure::mean_times;

const WORLDS: usize = 8;
const SECONDS: f64 = 2.0;

/// One world stacking for `SECONDS`; its ticks.
fn world() -> u64 {
    let ticks = Rc::new(std::cell::Cell::new(0));
    let counted = Rc::clone(&ticks);
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .behaviour(move |pl| async move {
            let _cut_short = pl.timeout(SECONDS, demos::stack(pl.clone())).await;
            counted.set(pl.ticks());
            Ok(())
        })
        .run()
        .expect("the run");
    ticks.get()
}

/// The process's resident memory in bytes.
fn resident() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
    let pages: u64 = statm
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse().ok())
        .unwrap_or(0);
    pages * 4096
}

/// The resident memory each of `count` bound PickAndPlaceWorlds takes, built by `builder`.
fn memory_per_world(builder: impl Fn() -> PlatformBuilder) -> f64 {
    let mut first = builder().build().expect("builds");
    first.step().expect("binds");
    let before = resident();
    let mut platforms = Vec::new();
    for _ in 0..WORLDS {
        let mut platform = builder().build().expect("builds");
        platform.step().expect("binds");
        platforms.push(platform);
    }
    let after = resident();
    drop(platforms);
    drop(first);
    (after.saturating_sub(before)) as f64 / WORLDS as f64
}

fn pick_and_place() -> PlatformBuilder {
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .behaviour(|pl| async move {
            pl.wait_forever().await?;
            Ok(())
        })
}

/// The time to build and bind the largest bundled world, with `[platform] model_cache` set to
/// `cache` (a TOML value).
fn start_up(cache: &str) -> Duration {
    let started = Instant::now();
    let mut platform = yarok::platform()
        .world::<GelTipWorld>()
        .set(&format!("platform/model_cache={cache}"))
        .expect("a setting")
        .behaviour(|pl| async move {
            pl.wait_forever().await?;
            Ok(())
        })
        .build()
        .expect("builds");
    platform.step().expect("binds");
    started.elapsed()
}

fn main() {
    let ticks = world();
    let [one, two] = mean_times(|threads| {
        let jobs: Vec<_> = (0..WORLDS).map(|_| world).collect();
        run_parallel(jobs, threads + 1)
    });
    println!(
        "{WORLDS} PickAndPlaceWorlds stacking, {SECONDS} s of platform time ({ticks} ticks) each:"
    );
    for (threads, time) in [(1, one), (2, two)] {
        println!(
            "  {threads} thread(s): {:>6.2} worlds/s  {:>8.0} ticks/s",
            WORLDS as f64 / time.as_secs_f64(),
            (WORLDS as u64 * ticks) as f64 / time.as_secs_f64()
        );
    }
    println!(
        "  2 threads do {:.2}× the work of 1",
        one.as_secs_f64() / two.as_secs_f64()
    );

    let shared = memory_per_world(pick_and_place);
    let own = memory_per_world(|| {
        pick_and_place().backend::<Sim>(|composition, _| Ok(SimBackend::new(composition)?))
    });
    println!(
        "memory per extra PickAndPlaceWorld (bound, {WORLDS} alive): {:.2} MB with the model \
         shared, {:.2} MB with a model of its own",
        shared / 1e6,
        own / 1e6
    );

    let composition = yarok::core::compose::compose::<GelTipWorld>().expect("composes");
    let models = tempfile::tempdir().unwrap();
    drop(Model::cached(&composition, Some(models.path())));
    let [compile, load] = mean_times(|variant| match variant {
        0 => Model::from_composition(&composition).expect("compiles"),
        _ => {
            let (model, source) = Model::cached(&composition, Some(models.path())).expect("loads");
            assert_eq!(source, ModelSource::Disk);
            Arc::try_unwrap(model).expect("no other world holds it")
        }
    });
    println!(
        "GelTipWorld's model: {:.2} ms compiled, {:.2} ms loaded from the cache ({:.1}× faster)",
        compile.as_secs_f64() * 1e3,
        load.as_secs_f64() * 1e3,
        compile.as_secs_f64() / load.as_secs_f64()
    );
    let folder = tempfile::tempdir().unwrap();
    let cache = format!("{:?}", folder.path().display().to_string());
    start_up(&cache);
    let [cold, cached] = mean_times(|variant| match variant {
        0 => start_up("false"),
        _ => start_up(&cache),
    });
    println!(
        "GelTipWorld start-up to its first tick: {:.1} ms compiled cold, {:.1} ms with the \
         model from the cache ({:.1}× faster)",
        cold.as_secs_f64() * 1e3,
        cached.as_secs_f64() * 1e3,
        cold.as_secs_f64() / cached.as_secs_f64()
    );
    #[cfg(feature = "zenoh")]
    zenoh_bridge::measure();
}
