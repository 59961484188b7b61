//! A sign of life while MuJoCo compiles a large world: its compiler gives no progress and its
//! time grows faster than the world's size (minutes for 10⁵ elements), so a user would
//! otherwise see a silent process.

use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use yarok_core::template::xml::Element;

/// How long a compile runs before it is announced.
const FIRST_NOTICE: Duration = Duration::from_secs(2);
/// How often a long compile is announced again.
const EVERY: Duration = Duration::from_secs(30);

/// Runs `compile` (of the world `mjcf`) on this thread while a watcher announces it once it
/// lasts past [`FIRST_NOTICE`] — with the world's size, counted only then — again every
/// [`EVERY`], and how long it took once it ended (warnings, which the platform's default
/// subscriber shows); a quick compile is silent and costs no count.
pub(crate) fn announcing_long<T>(mjcf: &Element, compile: impl FnOnce() -> T) -> T {
    let (done, finished) = mpsc::channel::<()>();
    let started = Instant::now();
    std::thread::scope(|scope| {
        let watcher = std::thread::Builder::new()
            .name("yarok-compile-notice".into())
            .spawn_scoped(scope, move || {
                let mut wait = FIRST_NOTICE;
                let mut announced = false;
                while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(wait) {
                    if announced {
                        let seconds = started.elapsed().as_secs();
                        tracing::warn!("MuJoCo is still compiling the world ({seconds} s so far)");
                    } else {
                        let elements = mjcf.descendants();
                        let bodies = elements.iter().filter(|e| e.name == "body").count();
                        tracing::warn!(
                            "MuJoCo is compiling a world of {} elements ({bodies} bodies); its \
                             compile time grows faster than a world's size, so this can take \
                             minutes; an interrupt (Ctrl-C) ends the process while no platform \
                             runs",
                            elements.len()
                        );
                    }
                    announced = true;
                    wait = EVERY;
                }
                if announced {
                    tracing::warn!(
                        "MuJoCo's compile ended after {:.1} s (with [platform] model_cache on, \
                         the next run of this world loads the compiled model from the cache)",
                        started.elapsed().as_secs_f64()
                    );
                }
            });
        let result = compile();
        drop(done);
        if let Ok(watcher) = watcher {
            let _ = watcher.join();
        }
        result
    })
}
