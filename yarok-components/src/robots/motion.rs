//! [`Motion`]: an arm's motion about to start — awaited until it arrives, or started and left
//! to run.

use std::fmt;
use std::future::{Future, IntoFuture};
use std::pin::Pin;

use yarok_core::time::{Clock, WaitError};

use super::motions::MotionEnding;

/// What runs an arm's motions (the UR arms' controller, a serial arm's): starts one toward a
/// goal, tells how one ended, stops one.
pub(crate) trait MotionControl {
    /// Where a motion goes.
    type Goal: fmt::Debug + Clone;
    /// Why a motion did not arrive.
    type Error: MotionEnding;
    /// Starts a motion, after checking its whole path; its id.
    fn start(&self, goal: Self::Goal, limits: Limits) -> Result<u64, Self::Error>;
    /// How motion `id` ended; `None` while it is under way.
    fn outcome(&self, id: u64) -> Option<Result<(), Self::Error>>;
    /// Stops motion `id` (any motion: `None`).
    fn stop(&self, id: Option<u64>);
    /// The platform's clock.
    fn clock(&self) -> &Clock;
}

/// An arm's motion about to start: set its speed and acceleration, then `.await` it (it
/// resolves on arrival) or [`Motion::start`] it and wait yourself (`pl.wait(|| arm.is_at(&q))`).
/// `E` is the arm's error: [`MotionError`](super::ur::MotionError) for the UR arms,
/// [`SerialMotionError`](super::serial::SerialMotionError) for a serial arm.
///
/// # Cancel safety
///
/// Dropping the awaited future before arrival stops the arm (as the arm's `stop`).
#[must_use = "a motion does nothing until awaited or started"]
pub struct Motion<'a, E> {
    request: Box<dyn Request<E> + 'a>,
    limits: Limits,
}

/// A motion's speed and acceleration, and whether the user chose them (or they are the
/// defaults, which a controller may lower to what the arm can follow).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Limits {
    pub(crate) speed: f64,
    pub(crate) acceleration: f64,
    pub(crate) chosen: bool,
}

/// A controller and the goal of the motion to start on it, with the controller's type erased.
trait Request<E>: fmt::Debug {
    fn start(&self, limits: Limits) -> Result<u64, E>;
    fn outcome(&self, id: u64) -> Option<Result<(), E>>;
    fn stop(&self, id: u64);
    fn clock(&self) -> &Clock;
    fn replaced(&self) -> E;
}

struct Bound<'a, C: MotionControl> {
    controller: &'a C,
    goal: C::Goal,
}

impl<C: MotionControl> fmt::Debug for Bound<'_, C> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.goal.fmt(f)
    }
}

impl<C: MotionControl> Request<C::Error> for Bound<'_, C> {
    fn start(&self, limits: Limits) -> Result<u64, C::Error> {
        self.controller.start(self.goal.clone(), limits)
    }

    fn outcome(&self, id: u64) -> Option<Result<(), C::Error>> {
        self.controller.outcome(id)
    }

    fn stop(&self, id: u64) {
        self.controller.stop(Some(id));
    }

    fn clock(&self) -> &Clock {
        self.controller.clock()
    }

    fn replaced(&self) -> C::Error {
        C::Error::replaced()
    }
}

impl<E> fmt::Debug for Motion<'_, E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Motion")
            .field("goal", &self.request)
            .field("limits", &self.limits)
            .finish()
    }
}

impl<'a, E> Motion<'a, E> {
    /// A motion of `controller` to `goal` at its default `(speed, acceleration)`.
    pub(crate) fn new<C: MotionControl<Error = E>>(
        controller: &'a C,
        goal: C::Goal,
        (speed, acceleration): (f64, f64),
    ) -> Self {
        Self {
            request: Box::new(Bound { controller, goal }),
            limits: Limits {
                speed,
                acceleration,
                chosen: false,
            },
        }
    }

    /// The speed: of the leading joint (rad/s) for `move_j`, of the TCP (m/s) for `move_l`.
    pub fn speed(mut self, speed: f64) -> Self {
        self.limits.speed = speed;
        self.limits.chosen = true;
        self
    }

    /// The acceleration: rad/s² for `move_j`, m/s² for `move_l`.
    pub fn acceleration(mut self, acceleration: f64) -> Self {
        self.limits.acceleration = acceleration;
        self.limits.chosen = true;
        self
    }

    /// Starts the motion and returns at once; it goes on until it arrives, is stopped or a
    /// newer motion replaces it.
    ///
    /// # Errors
    ///
    /// The arm's error when the target or a point on the way cannot be reached, or the limits
    /// are not positive numbers: nothing moves then.
    pub fn start(self) -> Result<(), E> {
        self.request.start(self.limits).map(drop)
    }
}

impl<'a, E: From<WaitError> + 'a> IntoFuture for Motion<'a, E> {
    type Output = Result<(), E>;
    type IntoFuture = Pin<Box<dyn Future<Output = Self::Output> + 'a>>;

    fn into_future(self) -> Self::IntoFuture {
        Box::pin(async move {
            let request = &*self.request;
            let id = request.start(self.limits)?;
            // Dropped with the future: stops the motion if it is still under way.
            let _stop_if_dropped = StopIfDropped { request, id };
            let mut outcome = None;
            request
                .clock()
                .wait(|| {
                    outcome = request.outcome(id);
                    outcome.is_some()
                })
                .await?;
            outcome.unwrap_or_else(|| Err(request.replaced()))
        })
    }
}

/// Stops motion `id` when its future is dropped before it ends.
struct StopIfDropped<'r, E> {
    request: &'r dyn Request<E>,
    id: u64,
}

impl<E> Drop for StopIfDropped<'_, E> {
    fn drop(&mut self) {
        self.request.stop(self.id);
    }
}
