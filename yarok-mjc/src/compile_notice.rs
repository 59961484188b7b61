//! A sign of life while MuJoCo compiles a large world: its compiler gives no progress and its
//! time grows faster than the world's size (minutes for 10⁵ elements), so a user would
//! otherwise see a silent process.

use std::sync::mpsc::{self, RecvTimeoutError, Sender};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long a compile runs before it is announced.
const FIRST_NOTICE: Duration = Duration::from_secs(2);
/// How often a long compile is announced again.
const EVERY: Duration = Duration::from_secs(30);

/// Announces a compile that lasts past [`FIRST_NOTICE`], then every [`EVERY`], and how long it
/// took once it ended (warnings, which the platform's default subscriber shows); silent for a quick
/// one. Dropping it ends the watch.
pub(crate) struct CompileNotice {
    done: Option<Sender<()>>,
    watcher: Option<JoinHandle<()>>,
}

impl CompileNotice {
    /// Starts watching a compile of `elements` MJCF elements, `bodies` of them bodies.
    pub(crate) fn start(elements: usize, bodies: usize) -> Self {
        let (done, finished) = mpsc::channel::<()>();
        let started = Instant::now();
        let watcher = std::thread::Builder::new()
            .name("yarok-compile-notice".into())
            .spawn(move || {
                let mut wait = FIRST_NOTICE;
                let mut announced = false;
                while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(wait) {
                    let seconds = started.elapsed().as_secs();
                    if announced {
                        tracing::warn!("MuJoCo is still compiling the world ({seconds} s so far)");
                    } else {
                        tracing::warn!(
                            "MuJoCo is compiling a world of {elements} elements ({bodies} \
                             bodies); its compile time grows faster than a world's size, so this \
                             can take minutes; an interrupt (Ctrl-C) ends the process while no \
                             platform runs"
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
            })
            .ok();
        Self {
            done: Some(done),
            watcher,
        }
    }
}

impl Drop for CompileNotice {
    fn drop(&mut self) {
        drop(self.done.take());
        if let Some(watcher) = self.watcher.take() {
            let _ = watcher.join();
        }
    }
}
