//! [`HardwareBackend`]: ticks at a fixed rate on the (tokio) wall clock.

use std::any::Any;

use tokio::time::Instant;
use yarok_core::compose::{Composition, Value};
use yarok_core::config::Settings;
use yarok_core::runtime::{Backend, RuntimeError};

/// Ticks per second when `[platform] tick_hz` is not set.
pub const DEFAULT_TICK_HZ: f64 = 100.0;

/// The `real` environment's backend: ticks are paced to the wall clock at `tick_hz`, platform
/// time is the monotonic time since start, and the devices' I/O happens in the components'
/// interfaces' per-tick steps.
///
/// Time comes from tokio's clock, so tests with `#[tokio::test(start_paused = true)]` run
/// hardware behaviours instantly.
#[derive(Debug)]
pub struct HardwareBackend {
    started: Instant,
    timestep: f64,
}

impl HardwareBackend {
    /// A backend ticking `tick_hz` times per second.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Backend`] unless `tick_hz` is a positive, finite rate.
    pub fn new(tick_hz: f64) -> Result<Self, RuntimeError> {
        if !(tick_hz.is_finite() && tick_hz > 0.0) {
            return Err(RuntimeError::Backend(format!(
                "[platform] tick_hz must be a positive rate, got {tick_hz}"
            )));
        }
        Ok(Self {
            started: Instant::now(),
            timestep: 1.0 / tick_hz,
        })
    }

    /// Makes the backend from the run settings (`[platform] tick_hz`), as a platform's
    /// [`backend`](yarok_core::runtime::PlatformBuilder::backend) factory.
    ///
    /// # Errors
    ///
    /// As [`HardwareBackend::new`], or when `tick_hz` is not a number.
    pub fn from_settings(
        _: &Composition,
        settings: &Settings,
    ) -> Result<Box<dyn Backend>, RuntimeError> {
        let tick_hz = match settings.platform.get("tick_hz") {
            None => DEFAULT_TICK_HZ,
            Some(Value::Float(hz)) => *hz,
            Some(Value::Int(hz)) => *hz as f64,
            Some(other) => {
                return Err(RuntimeError::Backend(format!(
                    "[platform] tick_hz must be a number, got {other:?}"
                )));
            }
        };
        Ok(Box::new(Self::new(tick_hz)?))
    }
}

impl Backend for HardwareBackend {
    fn step(&mut self) -> Result<(), RuntimeError> {
        Ok(())
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

    fn as_any(&self) -> &dyn Any {
        self
    }
}
