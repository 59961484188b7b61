//! Measures, side by side in one run, the platform loop against a raw `mj_step` loop on the same
//! model with contacts (a tumble tower of 24 blocks on a floor): steps/s of each, their ratio
//! (target ≥ 95 %), and the executor's overhead per tick in µs, with ten behaviours each holding
//! a pending wait that is checked every tick.
//!
//! ```text
//! cargo bench --bench platform
//! ```

use std::time::Instant;

use yarok::components::worlds::TowerWorld;
use yarok::core::compose::compose;
use yarok::mjc::{Data, Model};
use yarok::{Component, Declaration};

/// Seconds of raw stepping each measurement aims for.
const MEASURE_SECONDS: f64 = 2.0;

/// Just a floor: stepping is so cheap that the executor's own cost shows.
struct Floor;
impl Component for Floor {
    fn declaration() -> Declaration {
        Declaration::new("floor_world").template(r#"<mujoco><worldbody><geom name="floor" type="plane" size="2 2 0.1"/></worldbody></mujoco>"#)
    }
}

const WAITS: usize = 10;

fn raw_steps_per_second<W: Component>(ticks: u64) -> f64 {
    let model = std::sync::Arc::new(
        Model::from_composition(&compose::<W>().expect("compose")).expect("compile"),
    );
    let mut data = Data::new(&model).expect("data");
    data.forward();
    let started = Instant::now();
    for _ in 0..ticks {
        data.step();
    }
    ticks as f64 / started.elapsed().as_secs_f64()
}

fn platform_steps_per_second<W: Component>(ticks: u64) -> f64 {
    let mut builder = yarok::platform().world::<W>();
    for _ in 0..WAITS {
        builder = builder.behaviour(move |pl| async move {
            let clock = pl.clone();
            pl.wait(move || clock.ticks() >= ticks).await?;
            Ok(())
        });
    }
    let platform = builder.build().expect("platform");
    let started = Instant::now();
    platform.run().expect("run");
    ticks as f64 / started.elapsed().as_secs_f64()
}

/// Raw and platform steps/s, alternated twice with the best of each kept, so that machine noise
/// hits both alike.
fn compare<W: Component>() -> (u64, f64, f64) {
    let probe = raw_steps_per_second::<W>(500);
    let ticks = (probe * MEASURE_SECONDS).max(1000.0) as u64;
    let (mut raw, mut platform) = (0.0f64, 0.0f64);
    for _ in 0..2 {
        raw = raw.max(raw_steps_per_second::<W>(ticks));
        platform = platform.max(platform_steps_per_second::<W>(ticks));
    }
    (ticks, raw, platform)
}

fn main() {
    println!("{WAITS} behaviours each hold a pending wait, checked every tick\n");
    println!(
        "{:<34} {:>12} {:>12} {:>9} {:>14}",
        "model", "raw steps/s", "platform", "ratio", "overhead/tick"
    );
    for (name, (ticks, raw, platform)) in [
        (
            "tumble tower (24 blocks, contacts)",
            compare::<TowerWorld>(),
        ),
        ("floor only (executor cost shows)", compare::<Floor>()),
    ] {
        println!(
            "{name:<34} {raw:>12.0} {platform:>12.0} {:>8.1}% {:>11.2} µs   ({ticks} steps)",
            100.0 * platform / raw,
            (1.0 / platform - 1.0 / raw) * 1e6
        );
    }
    println!("\ntarget: platform ≥ 95 % of raw on the model with contacts");
}
