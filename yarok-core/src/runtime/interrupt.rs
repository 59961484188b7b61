//! Ctrl-C, SIGTERM and SIGHUP while platforms run, and their default effect once none does.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

/// The signals that stop a platform cleanly: Ctrl-C, and what schedulers (Slurm, Kubernetes,
/// systemd) and closing terminals send.
const SIGNALS: [i32; 3] = [SIGINT, SIGTERM, SIGHUP];

/// How many platforms listen for the signals now.
static LISTENING: Mutex<usize> = Mutex::new(0);

/// Set while no platform listens: the signals then have their default effect (the process
/// ends).
///
/// signal-hook keeps its own handler installed once anything registered for a signal, and does
/// not put the default disposition back when the last action is unregistered, so without this a
/// Ctrl-C after `run()` would be swallowed for the rest of the process.
static IDLE: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// A signal while a platform runs: the first one stops it cleanly (it sets the platform's stop
/// flag, checked every tick, and notes which signal it was); a second one, if shutdown hangs,
/// exits the process with the conventional status (128 + the signal's number: 130 for Ctrl-C,
/// 143 for SIGTERM, 129 for SIGHUP).
pub(super) struct Interrupt {
    signal: Arc<AtomicUsize>,
    handlers: Vec<signal_hook::SigId>,
}

impl Interrupt {
    pub(super) fn listen(stop: &Arc<AtomicBool>) -> Self {
        let mut listening = LISTENING.lock().unwrap_or_else(PoisonError::into_inner);
        *listening += 1;
        idle().store(false, Ordering::SeqCst);
        drop(listening);
        let signalled = Arc::new(AtomicBool::new(false));
        let signal = Arc::new(AtomicUsize::new(0));
        let handlers = SIGNALS
            .into_iter()
            .flat_map(|number| {
                let value = usize::try_from(number).unwrap_or_default();
                // The shutdown first, so that it sees the flag as the previous signal left it.
                [
                    signal_hook::flag::register_conditional_shutdown(
                        number,
                        128 + number,
                        Arc::clone(&signalled),
                    ),
                    signal_hook::flag::register(number, Arc::clone(&signalled)),
                    signal_hook::flag::register_usize(number, Arc::clone(&signal), value),
                    signal_hook::flag::register(number, Arc::clone(stop)),
                ]
            })
            .filter_map(|registered| {
                registered
                    .map_err(|error| {
                        tracing::warn!(%error, "a signal will not stop the platform cleanly")
                    })
                    .ok()
            })
            .collect();
        Self { signal, handlers }
    }

    /// The signal that asked the platform to stop, if one did.
    pub(super) fn signal(&self) -> Option<i32> {
        match self.signal.load(Ordering::Relaxed) {
            0 => None,
            number => i32::try_from(number).ok(),
        }
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

/// The idle flag, with the actions that give the signals their default effect while it is set
/// (registered once per process, before any platform's own actions).
fn idle() -> &'static AtomicBool {
    IDLE.get_or_init(|| {
        let idle = Arc::new(AtomicBool::new(true));
        for number in SIGNALS {
            if let Err(error) =
                signal_hook::flag::register_conditional_default(number, Arc::clone(&idle))
            {
                tracing::warn!(%error, number, "a signal may be ignored after the platform stops");
            }
        }
        idle
    })
}
