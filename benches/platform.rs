//! Measures, side by side in one run, the platform loop against a raw `mj_step` loop on the same
//! model: with contacts (a tumble tower of 24 blocks on a floor; target ≥ 95 %) and a bare floor
//! (where only the executor's cost shows; target ≥ 85 %): steps/s of each, their ratio, and the
//! platform's overhead per tick in µs, with ten behaviours each holding a pending wait that is
//! checked every tick.
//!
//! ```text
//! cargo bench --bench platform
//! ```
//!
//! Raw stepping and the platform take turns in short rounds, so that machine noise (another
//! process, frequency changes) hits both alike; each side's fastest round is reported (noise
//! only ever slows a round down), and so is the median of the rounds' ratios.

use std::cell::Cell;
use std::rc::Rc;
use std::time::Instant;

use yarok::components::worlds::TowerWorld;
use yarok::core::compose::compose;
use yarok::mjc::{Data, Model};
use yarok::{Component, Declaration};

/// Seconds of raw stepping a round aims for.
const ROUND_SECONDS: f64 = 0.01;

/// Seconds of stepping, both sides together, that each model's measurement aims for.
const MEASURE_SECONDS: f64 = 3.0;

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

/// Seconds for `ticks` platform ticks, timed by the first behaviour from its first poll to the
/// tick its wait resolves on: building, binding and shutting down are not counted, so that
/// rounds can be short.
fn platform_seconds<W: Component>(ticks: u64) -> f64 {
    let elapsed = Rc::new(Cell::new(f64::NAN));
    let mut builder = yarok::platform().world::<W>();
    for index in 0..WAITS {
        let elapsed = Rc::clone(&elapsed);
        builder = builder.behaviour(move |pl| async move {
            let started = Instant::now();
            let clock = pl.clone();
            pl.wait(move || clock.ticks() >= ticks).await?;
            if index == 0 {
                elapsed.set(started.elapsed().as_secs_f64());
            }
            Ok(())
        });
    }
    builder.build().expect("platform").run().expect("run");
    elapsed.get()
}

/// What [`compare`] measured.
struct Comparison {
    rounds: usize,
    ticks: u64,
    /// Steps/s of the fastest raw and platform rounds.
    raw: f64,
    platform: f64,
    /// The median of the rounds' platform/raw speed ratios.
    median_ratio: f64,
}

/// Raw stepping and the platform in alternating rounds.
fn compare<W: Component>() -> Comparison {
    let probe = 500.0 / raw_seconds::<W>(500);
    let ticks = (probe * ROUND_SECONDS).max(100.0) as u64;
    let rounds = ((MEASURE_SECONDS * probe / (2 * ticks) as f64) as usize).clamp(11, 151);
    let times: Vec<(f64, f64)> = (0..rounds)
        .map(|_| (raw_seconds::<W>(ticks), platform_seconds::<W>(ticks)))
        .collect();
    let fastest =
        |side: fn(&(f64, f64)) -> f64| times.iter().map(side).fold(f64::INFINITY, f64::min);
    let mut ratios: Vec<f64> = times.iter().map(|(raw, platform)| raw / platform).collect();
    ratios.sort_by(f64::total_cmp);
    Comparison {
        rounds,
        ticks,
        raw: ticks as f64 / fastest(|t| t.0),
        platform: ticks as f64 / fastest(|t| t.1),
        median_ratio: ratios[rounds / 2],
    }
}

fn main() {
    println!("{WAITS} behaviours each hold a pending wait, checked every tick\n");
    println!(
        "{:<34} {:>12} {:>12} {:>7} {:>14} {:>13}",
        "model", "raw steps/s", "platform", "ratio", "overhead/tick", "median ratio"
    );
    for (name, measured) in [
        (
            "tumble tower (24 blocks, contacts)",
            compare::<TowerWorld>(),
        ),
        ("floor only (executor cost shows)", compare::<Floor>()),
    ] {
        let Comparison {
            rounds,
            ticks,
            raw,
            platform,
            median_ratio,
        } = measured;
        println!(
            "{name:<34} {raw:>12.0} {platform:>12.0} {:>6.1}% {:>11.3} µs {:>12.1}%   ({rounds} rounds × {ticks} steps)",
            100.0 * platform / raw,
            (1.0 / platform - 1.0 / raw) * 1e6,
            100.0 * median_ratio,
        );
    }
    println!(
        "\nsteps/s: each side's fastest round; targets: platform ≥ 95 % of raw with contacts, \
         ≥ 85 % on the floor only"
    );
}
