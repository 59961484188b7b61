//! Shared by the benchmarks: run a piece of work repeatedly for a while.

use std::time::{Duration, Instant};

/// How long each measurement runs.
pub(crate) const MEASURE: Duration = Duration::from_secs(2);

/// Runs `work` once to warm up, then repeatedly for at least [`MEASURE`]; returns the mean time
/// of one run.
pub(crate) fn mean_time(mut work: impl FnMut()) -> Duration {
    work();
    let started = Instant::now();
    let mut runs = 0u32;
    while started.elapsed() < MEASURE {
        work();
        runs += 1;
    }
    started.elapsed() / runs
}
