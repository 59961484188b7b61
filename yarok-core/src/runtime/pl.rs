//! [`Pl`]: the handle behaviours get — platform time, waits, components.

use std::cell::RefCell;
use std::ops::Deref;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::component::{HandleError, Handles};
use crate::time::Clock;
use crate::value::Config;

/// The handle behaviours and plugins use: platform time and waits (it dereferences to the
/// platform's [`Clock`]: `pl.wait(…)`, `pl.wait_seconds(…)`, `pl.timeout(…)`, `pl.time()`),
/// components by path, the behaviour's settings.
///
/// Cheap to clone; lives on the platform's thread (it is not `Send`).
#[derive(Clone)]
pub struct Pl {
    /// Outside `inner`, so that reading time in a wait's condition is one indirection less.
    clock: Clock,
    inner: Rc<Shared>,
}

struct Shared {
    environment: String,
    handles: Rc<RefCell<Handles>>,
    behaviour: Config,
    stop: Arc<AtomicBool>,
}

impl std::fmt::Debug for Pl {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pl")
            .field("environment", &self.inner.environment)
            .field("time", &self.time())
            .finish()
    }
}

impl Deref for Pl {
    type Target = Clock;

    fn deref(&self) -> &Clock {
        &self.clock
    }
}

impl Pl {
    pub(crate) fn new(
        clock: Clock,
        environment: String,
        handles: Rc<RefCell<Handles>>,
        behaviour: Config,
        stop: Arc<AtomicBool>,
    ) -> Self {
        Self {
            clock,
            inner: Rc::new(Shared {
                environment,
                handles,
                behaviour,
                stop,
            }),
        }
    }

    /// The running environment's name.
    pub fn environment(&self) -> &str {
        &self.inner.environment
    }

    /// The behaviour's settings (`[behaviour]`), defaults applied.
    pub fn config(&self) -> &Config {
        &self.inner.behaviour
    }

    /// The component at `path` (`/arm`, `/arm/gripper`), or the one component named `path`'s
    /// last segment when `path` has no `/`.
    ///
    /// # Errors
    ///
    /// [`HandleError`]: no such component (with the nearest path), another type, or a
    /// component without a run-time interface.
    pub fn get<C: Clone + 'static>(&self, path: &str) -> Result<C, HandleError> {
        self.inner.handles.borrow().get(path)
    }

    /// Asks the platform to stop after the current tick; `run` then returns `Ok`.
    pub fn stop(&self) {
        self.inner.stop.store(true, Ordering::Relaxed);
    }
}
