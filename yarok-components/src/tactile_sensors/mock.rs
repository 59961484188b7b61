//! A tactile sensor in `mock`: nothing presses its gel, so its frame is the untouched gel.

use yarok_core::component::{Bind, BindError, Mock};
use yarok_mjc::DepthImage;

use super::kind::SensorKind;
use super::modelled::{GelSensing, Modelled, Touch};
use super::sensor::TactileSensor;

/// Senses nothing.
struct Untouched;

impl GelSensing for Untouched {
    fn see(&self, _depth: &mut DepthImage) -> Result<(), String> {
        Ok(())
    }

    fn touches(&self) -> Vec<Touch> {
        Vec::new()
    }
}

impl TactileSensor {
    /// Binds a sensor of `kind` in `mock`: its frames are the untouched gel's.
    pub(super) fn bind_mock(
        kind: &dyn SensorKind,
        bind: &mut Bind<Mock>,
    ) -> Result<Self, BindError> {
        Modelled::bind(kind, bind, Box::new(Untouched))
    }
}
