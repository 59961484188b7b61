//! [`Real`] and its [`HardwareBackend`]: ticks at a fixed rate on the (tokio) wall clock.

use tokio::time::Instant;
use yarok_core::BoxError;
use yarok_core::component::{Backend, Environment};
use yarok_core::compose::Composition;
use yarok_core::config::{ConfigError, Settings};

/// Ticks per second when `[platform] tick_hz` is not set.
pub const DEFAULT_TICK_HZ: f64 = 100.0;

/// The `real` environment: devices. Components' `Interface<Real>` implementations connect to
/// their device in their (async) bind, spawn its reader, and register a stop action.
#[derive(Debug, Clone, Copy)]
pub struct Real;

impl Environment for Real {
    const NAME: &'static str = "real";
    type Backend = HardwareBackend;
}

/// The `real` environment's backend: ticks are paced to the wall clock at `tick_hz`, platform
/// time is the monotonic time since start, and the devices' I/O happens in the components'
/// tasks and per-tick steps.
///
/// Time comes from tokio's clock, so tests with `#[tokio::test(start_paused = true)]` run
/// hardware behaviours instantly.
#[derive(Debug)]
pub struct HardwareBackend {
    started: Instant,
    timestep: f64,
}

/// The tick rate is not a positive, finite number.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("[platform] tick_hz must be a positive rate, got {0}")]
pub struct InvalidTickRate(pub f64);

impl HardwareBackend {
    /// A backend ticking `tick_hz` times per second.
    ///
    /// # Errors
    ///
    /// [`InvalidTickRate`] unless `tick_hz` is a positive, finite rate.
    pub fn new(tick_hz: f64) -> Result<Self, InvalidTickRate> {
        if !(tick_hz.is_finite() && tick_hz > 0.0) {
            return Err(InvalidTickRate(tick_hz));
        }
        Ok(Self {
            started: Instant::now(),
            timestep: 1.0 / tick_hz,
        })
    }

    /// Makes the backend from the run settings (`[platform] tick_hz`), as a platform's backend
    /// factory: `builder.backend::<Real>(HardwareBackend::from_settings)`.
    ///
    /// # Errors
    ///
    /// As [`HardwareBackend::new`], or [`ConfigError`] when `tick_hz` is not a number.
    pub fn from_settings(_: &Composition, settings: &Settings) -> Result<Self, BoxError> {
        let platform = settings
            .platform_settings()
            .map_err(|e: ConfigError| Box::new(e) as BoxError)?;
        Ok(Self::new(platform.tick_hz)?)
    }
}

impl Backend for HardwareBackend {
    fn step(&self) -> Result<f64, BoxError> {
        Ok(self.time())
    }

    fn time(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }

    fn timestep(&self) -> f64 {
        self.timestep
    }

    fn paced(&self) -> bool {
        true
    }
}
