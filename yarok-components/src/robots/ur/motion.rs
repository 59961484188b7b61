//! [`Move`]: a motion about to start — awaited until it arrives, or started and left to run.

use std::future::{Future, IntoFuture};
use std::pin::Pin;

use super::controller::{Controller, Goal};
use super::error::MotionError;

/// A motion about to start: set its speed and acceleration, then `.await` it (it resolves on
/// arrival) or [`Move::start`] it and wait yourself (`pl.wait(|| arm.is_at(&q))`).
///
/// # Cancel safety
///
/// Dropping the awaited future before arrival stops the arm (as [`Arm::stop`](super::Arm::stop)).
#[must_use = "a motion does nothing until awaited or started"]
pub struct Move<'a> {
    pub(super) controller: &'a Controller,
    pub(super) goal: Goal,
    pub(super) speed: f64,
    pub(super) acceleration: f64,
}

impl std::fmt::Debug for Move<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Move")
            .field("goal", &self.goal)
            .field("speed", &self.speed)
            .field("acceleration", &self.acceleration)
            .finish()
    }
}

impl Move<'_> {
    /// The speed: of the leading joint (rad/s) for `move_j`, of the TCP (m/s) for `move_l`.
    pub fn speed(mut self, speed: f64) -> Self {
        self.speed = speed;
        self
    }

    /// The acceleration: rad/s² for `move_j`, m/s² for `move_l`.
    pub fn acceleration(mut self, acceleration: f64) -> Self {
        self.acceleration = acceleration;
        self
    }

    /// Starts the motion and returns at once; it goes on until it arrives, is stopped or a
    /// newer motion replaces it.
    ///
    /// # Errors
    ///
    /// [`MotionError`] when the target or a point on the way cannot be reached, or the limits
    /// are not positive numbers: nothing moves then.
    pub fn start(self) -> Result<(), MotionError> {
        self.controller
            .start(self.goal, self.speed, self.acceleration)
            .map(drop)
    }
}

impl<'a> IntoFuture for Move<'a> {
    type Output = Result<(), MotionError>;
    type IntoFuture = Pin<Box<dyn Future<Output = Self::Output> + 'a>>;

    fn into_future(self) -> Self::IntoFuture {
        Box::pin(async move {
            let controller = self.controller;
            let id = controller.start(self.goal, self.speed, self.acceleration)?;
            // Dropped with the future: stops the motion if it is still under way.
            let _stop_if_dropped = StopIfDropped { controller, id };
            let mut outcome = None;
            controller
                .clock()
                .wait(|| {
                    outcome = controller.outcome(id);
                    outcome.is_some()
                })
                .await?;
            outcome.unwrap_or(Err(MotionError::Replaced))
        })
    }
}

/// Stops motion `id` when its future is dropped before it ends.
struct StopIfDropped<'a> {
    controller: &'a Controller,
    id: u64,
}

impl Drop for StopIfDropped<'_> {
    fn drop(&mut self) {
        self.controller.stop(Some(self.id));
    }
}
