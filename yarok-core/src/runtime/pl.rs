//! [`Pl`]: the handle behaviours get — platform time, waits, components.

use std::cell::{Cell, RefCell};
use std::ops::Deref;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use super::episode::{Episode, EpisodeError, Happening};
use crate::component::{Backend, HandleError, Handles, Lifecycle};
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
    /// What behaviours did since their last turn began, kept when plugins may read it.
    happenings: RefCell<Vec<Happening>>,
    keeps_happenings: bool,
    /// What an episode's beginning puts back: the backend's state, components' own.
    backend: Rc<dyn Backend>,
    lifecycle: Rc<RefCell<Lifecycle>>,
    episode: Cell<Option<Episode>>,
    /// The numbers of the episodes begun in this run.
    episodes_begun: RefCell<std::collections::BTreeSet<u64>>,
}

/// What the platform hands its [`Pl`].
pub(crate) struct PlParts {
    pub(crate) environment: String,
    pub(crate) handles: Rc<RefCell<Handles>>,
    pub(crate) behaviour: Config,
    pub(crate) stop: Arc<AtomicBool>,
    /// Whether plugins read what behaviours log and do (else it is not kept).
    pub(crate) keeps_happenings: bool,
    pub(crate) shard: Shard,
    /// The backend and the components' registrations, which an episode's beginning puts back.
    pub(crate) backend: Rc<dyn Backend>,
    pub(crate) lifecycle: Rc<RefCell<Lifecycle>>,
}

/// A line a behaviour logged with [`Pl::log`], and when.
#[derive(Debug, Clone, PartialEq)]
pub struct LogLine {
    /// Platform time (seconds) when it was logged.
    pub time: f64,
    /// The platform's tick count when it was logged.
    pub tick: u64,
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
    pub(crate) fn new(clock: Clock, parts: PlParts) -> Self {
        Self {
            clock,
            inner: Rc::new(Shared {
                environment: parts.environment,
                handles: parts.handles,
                behaviour: parts.behaviour,
                stop: parts.stop,
                happenings: RefCell::new(Vec::new()),
                keeps_happenings: parts.keeps_happenings,
                shard: parts.shard,
                backend: parts.backend,
                lifecycle: parts.lifecycle,
                episode: Cell::new(None),
                episodes_begun: RefCell::default(),
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

    /// Prints `line` on standard output (if it is still open: see [`crate::stdout`]) and keeps it, with the platform time, for plugins
    /// ([`World::happenings`](super::World::happenings)): a recorder stores it beside the run's
    /// data.
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
        crate::stdout::print_line(&text);
        let line = LogLine {
            time: self.time(),
            tick: self.ticks(),
            text,
        };
        self.keep(Happening::Logged(line));
    }

    /// Says, in words, what the behaviour is doing from now on (`"pick up the block"`): a
    /// dataset recorder labels the frames it takes from now with it, as the task a policy
    /// learns to do. Plugins see it among the [happenings](super::World::happenings).
    ///
    /// # Examples
    ///
    /// ```
    /// # async fn behaviour(pl: yarok_core::runtime::Pl) -> yarok_core::runtime::BehaviourResult {
    /// pl.set_task("pick up the block and put it down to the right");
    /// pl.wait_seconds(0.1).await?;
    /// # Ok(())
    /// # }
    /// ```
    pub fn set_task(&self, task: impl Into<String>) {
        self.keep(Happening::TaskSet(task.into()));
    }

    /// What behaviours did since their last turn began.
    pub(crate) fn happenings(&self) -> std::cell::Ref<'_, [Happening]> {
        std::cell::Ref::map(self.inner.happenings.borrow(), Vec::as_slice)
    }

    /// Forgets what behaviours did so far: every plugin has seen it.
    pub(crate) fn clear_happenings(&self) {
        self.inner.happenings.borrow_mut().clear();
    }

    /// Keeps `happening` for plugins, when there are any.
    fn keep(&self, happening: Happening) {
        if self.inner.keeps_happenings {
            self.inner.happenings.borrow_mut().push(happening);
        }
    }

    /// Begins episode `number` (ending the current one): the world goes back to the state it
    /// started in — in `sim` every body, joint, control and the solver's warm start, and every
    /// component's own state through its [restart action](crate::component::Bind::on_restart)
    /// — while platform time goes on. On hardware, where nothing can be put back, the episode
    /// only begins: the behaviour moves the devices where it needs them.
    ///
    /// Plugins see episodes begin and end ([`World::happenings`](super::World::happenings));
    /// yarok's MCAP recorder writes each apart, timed from its beginning, so an episode's
    /// recording is the same whichever episodes ran before it: the episodes of a sharded run
    /// ([`Pl::shard`]) are, between the shards, the whole run's, byte for byte.
    ///
    /// # Errors
    ///
    /// [`EpisodeError::Restart`] when the backend cannot put the world back;
    /// [`EpisodeError::Repeated`] for a number this run began before (its recordings would be
    /// overwritten). No episode is current then.
    ///
    /// # Examples
    ///
    /// ```
    /// # async fn behaviour(pl: yarok_core::runtime::Pl) -> yarok_core::runtime::BehaviourResult {
    /// for (number, depth) in pl.shard().select([0.5, 1.0, 1.5]) {
    ///     pl.begin_episode(number as u64)?;
    ///     pl.log(format!("pressing {depth} mm deep"));
    ///     pl.wait_seconds(0.1).await?;
    /// }
    /// pl.end_episode();
    /// # Ok(())
    /// # }
    /// ```
    pub fn begin_episode(&self, number: u64) -> Result<Episode, EpisodeError> {
        self.end_episode();
        if !self.inner.episodes_begun.borrow_mut().insert(number) {
            return Err(EpisodeError::Repeated { number });
        }
        self.restart_world()
            .map_err(|source| EpisodeError::Restart { number, source })?;
        let episode = Episode {
            number,
            start_tick: self.ticks(),
        };
        self.inner.episode.set(Some(episode));
        self.keep(Happening::EpisodeBegan(episode));
        Ok(episode)
    }

    /// Puts the world back into its start state: the backend's, then every component's restart
    /// action in binding order.
    pub(crate) fn restart_world(&self) -> Result<(), crate::BoxError> {
        self.inner.backend.restart()?;
        for restart in &mut self.inner.lifecycle.borrow_mut().restarts {
            restart();
        }
        Ok(())
    }

    /// Ends the current episode, if any (the next [`Pl::begin_episode`] and the run's end
    /// end it too).
    pub fn end_episode(&self) {
        if let Some(episode) = self.inner.episode.take() {
            self.keep(Happening::EpisodeEnded(episode));
        }
    }

    /// The current episode.
    pub fn episode(&self) -> Option<Episode> {
        self.inner.episode.get()
    }

    /// Asks the platform to stop after the current tick; `run` then returns `Ok`.
    pub fn stop(&self) {
        self.inner.stop.store(true, Ordering::Relaxed);
    }

    /// Whether the platform was asked to stop: by [`Pl::stop`], its
    /// [stop flag](super::Platform::stop_flag) or a signal (Ctrl-C). A plugin that waits at the
    /// run's end (a viewer kept open) stops waiting then.
    pub fn stop_requested(&self) -> bool {
        self.inner.stop.load(Ordering::Relaxed)
    }
}
