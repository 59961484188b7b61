//! [`Pl`]: the handle behaviours get — platform time, waits, components.

use std::cell::RefCell;
use std::ops::Deref;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::component::{HandleError, Handles};
use crate::config::Shard;
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
    shard: Shard,
    /// Lines logged since the behaviours' last turn began, kept when plugins may read them.
    log: RefCell<Vec<LogLine>>,
    keeps_log: bool,
}

/// A line a behaviour logged with [`Pl::log`], and when.
#[derive(Debug, Clone, PartialEq)]
pub struct LogLine {
    /// Platform time (seconds) when it was logged.
    pub time: f64,
    /// The line.
    pub text: String,
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
        keeps_log: bool,
        shard: Shard,
    ) -> Self {
        Self {
            clock,
            inner: Rc::new(Shared {
                environment,
                handles,
                behaviour,
                stop,
                log: RefCell::new(Vec::new()),
                keeps_log,
                shard,
            }),
        }
    }

    /// The running environment's name.
    pub fn environment(&self) -> &str {
        &self.inner.environment
    }

    /// Which share of its work this run does (`[platform] shard`; the whole by default): a
    /// behaviour with a grid of parameters or a list of episodes does the items
    /// [`Shard::select`] gives it.
    pub fn shard(&self) -> Shard {
        self.inner.shard
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

    /// Prints `line` on standard output and keeps it, with the platform time, for plugins
    /// ([`World::log`](super::World::log)): a recorder stores it beside the run's data.
    ///
    /// # Examples
    ///
    /// ```
    /// # async fn behaviour(pl: yarok_core::runtime::Pl) {
    /// pl.log(format!("{:.2} s: the block is grasped", pl.time()));
    /// # }
    /// ```
    pub fn log(&self, line: impl Into<String>) {
        let text = line.into();
        println!("{text}");
        if self.inner.keeps_log {
            self.inner.log.borrow_mut().push(LogLine {
                time: self.time(),
                text,
            });
        }
    }

    /// The lines logged since the behaviours' last turn began.
    pub(crate) fn logged(&self) -> std::cell::Ref<'_, [LogLine]> {
        std::cell::Ref::map(self.inner.log.borrow(), Vec::as_slice)
    }

    /// Forgets the lines logged so far: every plugin has seen them.
    pub(crate) fn clear_log(&self) {
        self.inner.log.borrow_mut().clear();
    }

    /// Asks the platform to stop after the current tick; `run` then returns `Ok`.
    pub fn stop(&self) {
        self.inner.stop.store(true, Ordering::Relaxed);
    }
}
