//! [`MockFingers`]: fingers that move at the requested speed and never meet an object.

use std::cell::RefCell;

use super::drive::{FingerDrive, Request};
use super::names::Stroke;
use super::ramp::Ramp;

/// A gripper's fingers with no simulation behind them: they follow each request at its speed
/// and reach it.
#[derive(Debug)]
pub struct MockFingers {
    stroke: Stroke,
    ramp: RefCell<Ramp>,
}

impl MockFingers {
    /// Fingers open at power-on, moving over `stroke`.
    pub fn new(stroke: Stroke) -> Self {
        Self {
            stroke,
            ramp: RefCell::new(Ramp::START),
        }
    }
}

impl FingerDrive for MockFingers {
    fn position(&self) -> f64 {
        self.ramp.borrow().command
    }

    fn is_moving(&self) -> bool {
        self.ramp.borrow().is_running()
    }

    fn requested(&self) -> Request {
        self.ramp.borrow().request
    }

    fn request(&self, request: Request) {
        let mut ramp = self.ramp.borrow_mut();
        let from = ramp.command;
        ramp.start(request, from);
    }

    fn tick(&self, timestep: f64) {
        self.ramp.borrow_mut().advance(&self.stroke, timestep);
    }

    fn restart(&self) {
        *self.ramp.borrow_mut() = Ramp::START;
    }
}
