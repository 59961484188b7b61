//! [`Backend`]: what the platform steps each tick — a simulator or devices.

use std::any::Any;
use std::cell::Cell;

use crate::BoxError;

/// The world a platform runs in: MuJoCo in `sim`, devices in `real`, nothing in `mock`.
///
/// The platform calls [`Backend::step`] once per tick, then the components' per-tick steps, then
/// the plugins. Interfaces reach their environment's backend, typed, through
/// [`Bind::backend`](super::Bind::backend); plugins through
/// [`World::backend`](crate::runtime::World::backend). Backends are shared (`&self`), so state
/// that changes lives in cells.
pub trait Backend: Any {
    /// Advances one tick: one simulation step, or one round of device I/O. Returns the platform
    /// time after it, what [`Backend::time`] now says.
    ///
    /// # Errors
    ///
    /// Whatever stops the world from advancing; the platform shuts down with it.
    fn step(&self) -> Result<f64, BoxError>;

    /// Platform time in seconds: simulation time, or time since start on hardware.
    fn time(&self) -> f64;

    /// Seconds per tick.
    fn timestep(&self) -> f64;

    /// Whether ticks should be paced to wall-clock time (always on hardware; optional in sim).
    fn paced(&self) -> bool;

    /// Remembers the world's state as the one [`Backend::restart`] puts back: called once,
    /// after every component has bound and before plugins and behaviours start.
    fn remember_start(&self) {}

    /// Puts the world back into the state [`Backend::remember_start`] remembered, keeping
    /// platform time; called when an episode begins
    /// ([`Pl::begin_episode`](crate::runtime::Pl::begin_episode)). By default nothing: on
    /// hardware nothing can be put back, and the behaviour moves the devices where it needs them.
    ///
    /// # Errors
    ///
    /// Whatever keeps the world from going back; the episode does not begin.
    fn restart(&self) -> Result<(), BoxError> {
        Ok(())
    }

    /// Called once at shutdown, after the components' stop actions.
    fn stop(&self) {}
}

/// A backend with nothing behind it: time advances by a fixed timestep per tick. For tests of
/// behaviours and plugins, and for components' `mock` interfaces.
///
/// It may carry a view of the world as it was declared ([`MockBackend::with_world`]), which
/// components' mock drives read: in yarok, the composed model at its initial state, with no
/// physics (`yarok_mjc::DeclaredWorld`).
#[derive(Clone)]
pub struct MockBackend {
    time: Cell<f64>,
    timestep: f64,
    paced: bool,
    world: Option<std::rc::Rc<dyn std::any::Any>>,
}

impl std::fmt::Debug for MockBackend {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MockBackend")
            .field("time", &self.time)
            .field("timestep", &self.timestep)
            .field("paced", &self.paced)
            .field("world", &self.world.is_some())
            .finish()
    }
}

impl MockBackend {
    /// A mock ticking `timestep` seconds per tick; `paced` ties ticks to (tokio) time.
    pub fn new(timestep: f64, paced: bool) -> Self {
        Self {
            time: Cell::new(0.0),
            timestep,
            paced,
            world: None,
        }
    }

    /// The mock with a view of the declared world attached, for components' mock drives to
    /// read ([`MockBackend::world`]).
    pub fn with_world(mut self, world: std::rc::Rc<dyn std::any::Any>) -> Self {
        self.world = Some(world);
        self
    }

    /// The view of the declared world attached, if it is a `T`.
    pub fn world<T: std::any::Any>(&self) -> Option<&T> {
        self.world.as_deref()?.downcast_ref()
    }
}

impl Backend for MockBackend {
    fn step(&self) -> Result<f64, BoxError> {
        self.time.set(self.time.get() + self.timestep);
        Ok(self.time.get())
    }

    fn time(&self) -> f64 {
        self.time.get()
    }

    fn timestep(&self) -> f64 {
        self.timestep
    }

    fn paced(&self) -> bool {
        self.paced
    }
}
