//! Measures, side by side in one run, the platform loop against a raw `mj_step` loop on the same
//! model: with contacts (a tumble tower of 24 blocks on a floor; target ≥ 95 %) and a bare floor
//! (where only the executor's cost shows; target ≥ 85 %): steps/s of each, their ratio, and the
//! platform's overhead per tick in µs, with ten behaviours each holding a pending wait that is
//! checked every tick.
//!
//! ```text
//! cargo bench --bench platform
//! ```

use std::time::Instant;

use yarok::components::worlds::TowerWorld;
use yarok::core::compose::compose;
use yarok::mjc::{Data, Model};
use yarok::{Component, Declaration};

/// Seconds of raw stepping each of the [`ROUNDS`] aims for.
const ROUND_SECONDS: f64 = 0.15;

/// Rounds the measurement is split into; raw and platform take turns within each round, so that
/// machine noise (another process, frequency changes) hits both alike, and the ratio reported is
/// the median of the rounds' ratios, so that one disturbed round does not decide it.
const ROUNDS: usize = 15;

/// Just a floor: stepping is so cheap that the executor's own cost shows.
struct Floor;
impl Component for Floor {
    fn declaration() -> Declaration {
        Declaration::new("floor_world").template(r#"<mujoco><worldbody><geom name="floor" type="plane" size="2 2 0.1"/></worldbody></mujoco>"#)
    }
}

const WAITS: usize = 10;

/// Seconds for `ticks` raw steps.
fn raw_seconds<W: Component>(ticks: u64) -> f64 {
    let model = std::sync::Arc::new(
        Model::from_composition(&compose::<W>().expect("compose")).expect("compile"),
    );
    let mut data = Data::new(&model).expect("data");
    data.forward();
    let started = Instant::now();
    for _ in 0..ticks {
        data.step();
    }
    started.elapsed().as_secs_f64()
}

/// Seconds for `ticks` platform ticks (building the platform is not counted).
fn platform_seconds<W: Component>(ticks: u64) -> f64 {
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
    started.elapsed().as_secs_f64()
}

/// Steps per tick measured in alternating rounds: (steps per round, the median round's raw and
/// platform steps/s).
fn compare<W: Component>() -> (u64, f64, f64) {
    let probe = 500.0 / raw_seconds::<W>(500);
    let ticks = (probe * ROUND_SECONDS).max(1000.0) as u64;
    let mut rounds: Vec<(f64, f64)> = (0..ROUNDS)
        .map(|_| (raw_seconds::<W>(ticks), platform_seconds::<W>(ticks)))
        .collect();
    rounds.sort_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)));
    let (raw, platform) = rounds[ROUNDS / 2];
    (ticks, ticks as f64 / raw, ticks as f64 / platform)
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
            "{name:<34} {raw:>12.0} {platform:>12.0} {:>8.1}% {:>11.2} µs   (median of {ROUNDS} × {ticks} steps)",
            100.0 * platform / raw,
            (1.0 / platform - 1.0 / raw) * 1e6
        );
    }
    println!("\ntargets: platform ≥ 95 % of raw with contacts, ≥ 85 % on the floor only");
}
