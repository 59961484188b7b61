//! [`Wait`]: the future behind every `pl.wait…`, resolved on platform ticks.

use std::fmt;
use std::future::Future;
use std::panic::Location;
use std::pin::Pin;
use std::task::{Context, Poll};

use super::ClockState;

/// Why a wait ended without its condition holding.
#[derive(Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum WaitError {
    /// The timeout (platform seconds) passed first.
    #[error("the wait made at {location} timed out after {seconds} s of platform time")]
    Timeout {
        /// The timeout that passed.
        seconds: f64,
        /// Where the wait was made (the behaviour's file, line and column).
        location: &'static Location<'static>,
    },
    /// The platform is shutting down.
    #[error("the platform stopped")]
    Stopped,
    /// A duration was NaN or negative; the wait ends at once with this error.
    #[error("{what}({seconds}) at {location}: a duration is a number of seconds, at least 0")]
    InvalidDuration {
        /// `wait_seconds` or `timeout`.
        what: &'static str,
        /// The duration given.
        seconds: f64,
        /// Where it was given.
        location: &'static Location<'static>,
    },
}

crate::debug_as_report!(WaitError);

impl WaitError {
    /// The error for `seconds` given to `what`, when it is not a valid duration.
    #[track_caller]
    pub(crate) fn check_duration(what: &'static str, seconds: f64) -> Option<Self> {
        let location = Location::caller();
        (seconds.is_nan() || seconds < 0.0).then_some(Self::InvalidDuration {
            what,
            seconds,
            location,
        })
    }
}

/// A wait for a condition, checked once after every platform tick (the first check after the
/// next tick: at least one tick always passes).
///
/// Build it with [`Clock::wait`](super::Clock::wait) and friends; refine it with
/// [`Wait::timeout`] and [`Wait::on_tick`]; `.await` it. A wait remembers where it was made, and
/// its errors say so.
///
/// # Cancel safety
///
/// Dropping a `Wait` cancels it; nothing else changes.
#[must_use = "a wait does nothing unless awaited"]
#[repr(C)] // What every tick reads first, together.
pub struct Wait<'a, C> {
    clock: &'a ClockState,
    /// The last tick the wait has seen; the tick it was made on, at first (`u64::MAX` when it is
    /// invalid: no tick is new to it then, and its first poll fails).
    seen_tick: u64,
    /// Platform time at which it times out.
    deadline: f64,
    condition: C,
    started_time: f64,
    timeout: Option<f64>,
    location: &'static Location<'static>,
    /// An error found while the wait was built, returned by its first poll.
    invalid: Option<WaitError>,
}

impl<'a, C: FnMut() -> bool + Unpin> Wait<'a, C> {
    #[track_caller]
    pub(crate) fn new(clock: &'a ClockState, condition: C) -> Self {
        Self {
            clock,
            seen_tick: clock.ticks.get(),
            deadline: f64::INFINITY,
            condition,
            started_time: clock.time.get(),
            timeout: None,
            location: Location::caller(),
            invalid: None,
        }
    }

    /// Ends the wait with `error` on its first poll.
    pub(crate) fn invalid(mut self, error: Option<WaitError>) -> Self {
        self.invalid = self.invalid.or(error);
        if self.invalid.is_some() {
            self.seen_tick = u64::MAX;
        }
        self
    }

    /// Fails with [`WaitError::Timeout`] once `seconds` of platform time pass without the
    /// condition holding. `f64::INFINITY` means no timeout; NaN or a negative number makes the
    /// wait fail at once with [`WaitError::InvalidDuration`].
    #[track_caller]
    pub fn timeout(mut self, seconds: f64) -> Self {
        self.timeout = Some(seconds);
        // Half a timestep of slack so that float time never adds or drops a tick.
        self.deadline = self
            .deadline
            .min(self.started_time + seconds - self.clock.timestep / 2.0);
        self.invalid(WaitError::check_duration("timeout", seconds))
    }

    /// Calls `callback` on every tick the wait sees, before checking the condition.
    pub fn on_tick(
        self,
        mut callback: impl FnMut() + Unpin + 'a,
    ) -> Wait<'a, impl FnMut() -> bool + Unpin + 'a>
    where
        C: 'a,
    {
        let mut condition = self.condition;
        Wait {
            clock: self.clock,
            seen_tick: self.seen_tick,
            deadline: self.deadline,
            condition: move || {
                callback();
                condition()
            },
            started_time: self.started_time,
            timeout: self.timeout,
            location: self.location,
            invalid: self.invalid,
        }
    }
}

impl<C: FnMut() -> bool + Unpin> Future for Wait<'_, C> {
    type Output = Result<(), WaitError>;

    #[inline]
    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        let this = self.get_mut();
        let ticks = this.clock.ticks.get();
        // A stopped clock ticks no more: a new tick means it runs.
        if ticks > this.seen_tick {
            this.seen_tick = ticks;
            if (this.condition)() {
                return Poll::Ready(Ok(()));
            }
            if this.clock.time.get() >= this.deadline {
                return Poll::Ready(Err(this.failure()));
            }
        } else if this.invalid.is_some() || this.clock.stopped.get() {
            return Poll::Ready(Err(this.failure()));
        }
        this.clock.register(cx.waker());
        Poll::Pending
    }
}

impl<C> Wait<'_, C> {
    /// Why the wait ends unresolved: invalid, stopped, or timed out.
    #[cold]
    fn failure(&self) -> WaitError {
        if let Some(error) = self.invalid {
            error
        } else if self.clock.stopped.get() {
            WaitError::Stopped
        } else {
            WaitError::Timeout {
                seconds: self.timeout.unwrap_or(f64::INFINITY),
                location: self.location,
            }
        }
    }
}

impl<C> fmt::Debug for Wait<'_, C> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Wait")
            .field("seen_tick", &self.seen_tick)
            .field("timeout", &self.timeout)
            .field("location", &self.location)
            .finish()
    }
}
