//! [`Backend`]: what the platform steps each tick — a simulator or devices.

use std::any::Any;

use super::RuntimeError;
use crate::compose::Composition;
use crate::config::Settings;

/// The world a platform runs in: MuJoCo in `sim`, devices in `real`, nothing in `mock`.
///
/// The platform calls [`Backend::step`] once per tick, then the components' interfaces, then the
/// plugins. Interfaces reach their backend through [`Bind::backend`](super::Bind::backend).
pub trait Backend: Any {
    /// Advances one tick: one simulation step, or one round of device I/O.
    ///
    /// # Errors
    ///
    /// Whatever stops the world from advancing; the platform shuts down with it.
    fn step(&mut self) -> Result<(), RuntimeError>;

    /// Platform time in seconds: simulation time, or time since start on hardware.
    fn time(&self) -> f64;

    /// Seconds per tick.
    fn timestep(&self) -> f64;

    /// Whether ticks should be paced to wall-clock time (always on hardware; optional in sim).
    fn paced(&self) -> bool;

    /// Leaves the world safe at shutdown (stop motion, close devices).
    fn stop(&mut self) {}

    /// The backend as `Any`, for interfaces to reach their concrete backend.
    fn as_any(&self) -> &dyn Any;
}

/// Makes the backend of one environment from the composed world and the run settings.
pub type BackendFactory =
    Box<dyn FnOnce(&Composition, &Settings) -> Result<Box<dyn Backend>, RuntimeError>>;

/// A backend with nothing behind it: time advances by a fixed timestep per tick. For tests of
/// behaviours and plugins, and for components' `mock` interfaces.
#[derive(Debug, Clone)]
pub struct MockBackend {
    time: f64,
    timestep: f64,
    paced: bool,
}

impl MockBackend {
    /// A mock ticking `timestep` seconds per tick; `paced` ties ticks to (tokio) time.
    pub fn new(timestep: f64, paced: bool) -> Self {
        Self {
            time: 0.0,
            timestep,
            paced,
        }
    }
}

impl Backend for MockBackend {
    fn step(&mut self) -> Result<(), RuntimeError> {
        self.time += self.timestep;
        Ok(())
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn timestep(&self) -> f64 {
        self.timestep
    }

    fn paced(&self) -> bool {
        self.paced
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
