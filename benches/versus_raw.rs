//! Shared by the benchmarks that set the platform loop against raw `mj_step` on the same model:
//! raw stepping and the platform take turns in short rounds, so that machine noise (another
//! process, frequency changes) hits both alike; each side's fastest round is reported (noise
//! only ever slows a round down), and so is the median of the rounds' ratios.

use std::cell::Cell;
use std::rc::Rc;
use std::time::Instant;

use yarok::Component;
use yarok::core::compose::compose;
use yarok::mjc::{Data, Model};

/// Seconds of raw stepping a round aims for.
const ROUND_SECONDS: f64 = 0.01;

/// Seconds of stepping, both sides together, that each model's measurement aims for.
const MEASURE_SECONDS: f64 = 3.0;

/// A new simulation of `W`, compiled on its own, in the state `prepare` sets up.
pub(crate) fn fresh_data<W: Component>(prepare: fn(&mut Data)) -> Data {
    let model = std::sync::Arc::new(
        Model::from_composition(&compose::<W>().expect("compose")).expect("compile"),
    );
    let mut data = Data::new(&model).expect("data");
    prepare(&mut data);
    data.forward();
    data
}

/// Seconds for `ticks` raw steps, from the state `prepare` sets up.
pub(crate) fn raw_seconds<W: Component>(ticks: u64, prepare: fn(&mut Data)) -> f64 {
    let mut data = fresh_data::<W>(prepare);
    let started = Instant::now();
    for _ in 0..ticks {
        data.step();
    }
    started.elapsed().as_secs_f64()
}

/// Seconds for `ticks` platform ticks, timed by the first behaviour from its first poll to the
/// tick its wait resolves on: building, binding and shutting down are not counted, so that
/// rounds can be short.
pub(crate) fn platform_seconds<W: Component>(ticks: u64, waits: usize) -> f64 {
    let elapsed = Rc::new(Cell::new(f64::NAN));
    let mut builder = yarok::platform().world::<W>();
    for index in 0..waits {
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
pub(crate) struct Comparison {
    pub(crate) rounds: usize,
    pub(crate) ticks: u64,
    /// Steps/s of the fastest raw and platform rounds.
    pub(crate) raw: f64,
    pub(crate) platform: f64,
    /// The median of the rounds' platform/raw speed ratios.
    pub(crate) median_ratio: f64,
}

impl Comparison {
    /// The fastest platform round's speed over the fastest raw round's.
    pub(crate) fn ratio(&self) -> f64 {
        self.platform / self.raw
    }

    /// µs a tick the platform adds to raw stepping (fastest rounds).
    pub(crate) fn overhead_us(&self) -> f64 {
        (1.0 / self.platform - 1.0 / self.raw) * 1e6
    }
}

/// Raw stepping (from the state `prepare` sets up: what the world's components do when they
/// bind) and the platform (with `waits` behaviours each holding a pending wait) in alternating
/// rounds.
pub(crate) fn compare<W: Component>(waits: usize, prepare: fn(&mut Data)) -> Comparison {
    compare_with::<W>(prepare, |ticks| platform_seconds::<W>(ticks, waits))
}

/// Raw stepping, as [`compare`], against `other`: seconds for a number of ticks.
pub(crate) fn compare_with<W: Component>(
    prepare: fn(&mut Data),
    other: impl Fn(u64) -> f64,
) -> Comparison {
    let probe = 500.0 / raw_seconds::<W>(500, prepare);
    let ticks = (probe * ROUND_SECONDS).max(100.0) as u64;
    let rounds = ((MEASURE_SECONDS * probe / (2 * ticks) as f64) as usize).clamp(11, 151);
    let times: Vec<(f64, f64)> = (0..rounds)
        .map(|_| (raw_seconds::<W>(ticks, prepare), other(ticks)))
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
