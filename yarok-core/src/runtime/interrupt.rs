//! Ctrl-C while platforms run, and its default effect once none does.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

use signal_hook::consts::SIGINT;

/// How many platforms listen for Ctrl-C now.
static LISTENING: Mutex<usize> = Mutex::new(0);

/// Set while no platform listens: Ctrl-C then has its default effect (the process ends).
///
/// signal-hook keeps its own handler installed once anything registered for a signal, and does
/// not put the default disposition back when the last action is unregistered, so without this a
/// Ctrl-C after `run()` would be swallowed for the rest of the process.
static IDLE: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// Ctrl-C while a platform runs: the first one stops it cleanly (it sets the platform's stop
/// flag, checked every tick, and its own, which says why it stopped); a second one, if shutdown
/// hangs, exits the process with status 130.
pub(super) struct Interrupt {
    flag: Arc<AtomicBool>,
    handlers: Vec<signal_hook::SigId>,
}

impl Interrupt {
    pub(super) fn listen(stop: &Arc<AtomicBool>) -> Self {
        let mut listening = LISTENING.lock().unwrap_or_else(PoisonError::into_inner);
        *listening += 1;
        idle().store(false, Ordering::SeqCst);
        drop(listening);
        let flag = Arc::new(AtomicBool::new(false));
        // Registered first, so that it sees the flag as the previous Ctrl-C left it.
        let handlers = [
            signal_hook::flag::register_conditional_shutdown(SIGINT, 130, Arc::clone(&flag)),
            signal_hook::flag::register(SIGINT, Arc::clone(&flag)),
            signal_hook::flag::register(SIGINT, Arc::clone(stop)),
        ]
        .into_iter()
        .filter_map(|registered| {
            registered
                .map_err(
                    |error| tracing::warn!(%error, "Ctrl-C will not stop the platform cleanly"),
                )
                .ok()
        })
        .collect();
        Self { flag, handlers }
    }

    pub(super) fn happened(&self) -> bool {
        self.flag.load(Ordering::Relaxed)
    }
}

impl Drop for Interrupt {
    fn drop(&mut self) {
        for handler in self.handlers.drain(..) {
            signal_hook::low_level::unregister(handler);
        }
        let mut listening = LISTENING.lock().unwrap_or_else(PoisonError::into_inner);
        *listening -= 1;
        if *listening == 0 {
            idle().store(true, Ordering::SeqCst);
        }
    }
}

/// The idle flag, with the action that gives Ctrl-C its default effect while it is set
/// (registered once per process, before any platform's own actions).
fn idle() -> &'static AtomicBool {
    IDLE.get_or_init(|| {
        let idle = Arc::new(AtomicBool::new(true));
        if let Err(error) =
            signal_hook::flag::register_conditional_default(SIGINT, Arc::clone(&idle))
        {
            tracing::warn!(%error, "Ctrl-C may be ignored after the platform stops");
        }
        idle
    })
}
