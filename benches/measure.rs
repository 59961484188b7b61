//! Shared by the benchmarks: time variants of a piece of work side by side.

use std::hint::black_box;
use std::time::{Duration, Instant};

/// How long each variant runs in all.
pub(crate) const MEASURE: Duration = Duration::from_secs(2);

/// Rounds the measurement is split into; the variants take turns within each round, so that
/// machine noise (another process, frequency changes) hits all of them alike.
const ROUNDS: u32 = 8;

/// The mean time of one run of each of `N` variants of `work` (`work(0)`, `work(1)`, …), each
/// run first once to warm up, then in turns for about [`MEASURE`] in all. What `work` returns
/// is kept alive with `black_box`, so that no run is optimised away.
pub(crate) fn mean_times<const N: usize, R>(mut work: impl FnMut(usize) -> R) -> [Duration; N] {
    for variant in 0..N {
        black_box(work(variant));
    }
    let mut spent = [Duration::ZERO; N];
    let mut runs = [0u32; N];
    for _ in 0..ROUNDS {
        for variant in 0..N {
            let started = Instant::now();
            while started.elapsed() < MEASURE / ROUNDS {
                black_box(work(variant));
                runs[variant] += 1;
            }
            spent[variant] += started.elapsed();
        }
    }
    std::array::from_fn(|variant| spent[variant] / runs[variant].max(1))
}
