//! [`Timeout`]: any future, with a deadline in platform time.

use std::future::Future;
use std::panic::Location;
use std::pin::Pin;
use std::task::{Context, Poll};

use super::{ClockState, WaitError};

/// A future with a deadline in platform time; made by
/// [`Clock::timeout`](super::Clock::timeout).
///
/// # Cancel safety
///
/// As cancel safe as the future it wraps.
#[must_use = "a timeout does nothing unless awaited"]
#[derive(Debug)]
pub struct Timeout<'a, F> {
    clock: &'a ClockState,
    future: Pin<Box<F>>,
    deadline: f64,
    seconds: f64,
    location: &'static Location<'static>,
    invalid: Option<WaitError>,
}

impl<'a, F: Future> Timeout<'a, F> {
    #[track_caller]
    pub(crate) fn new(clock: &'a ClockState, seconds: f64, future: F) -> Self {
        Self {
            clock,
            future: Box::pin(future),
            // Half a timestep of slack so that float time never adds or drops a tick.
            deadline: clock.time.get() + seconds - clock.timestep / 2.0,
            seconds,
            location: Location::caller(),
            invalid: WaitError::check_duration("timeout", seconds),
        }
    }
}

impl<F: Future> Future for Timeout<'_, F> {
    type Output = Result<F::Output, WaitError>;

    fn poll(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        if let Some(error) = self.invalid {
            return Poll::Ready(Err(error));
        }
        if let Poll::Ready(output) = self.future.as_mut().poll(cx) {
            return Poll::Ready(Ok(output));
        }
        if self.clock.stopped.get() {
            return Poll::Ready(Err(WaitError::Stopped));
        }
        if self.clock.time.get() >= self.deadline {
            return Poll::Ready(Err(WaitError::Timeout {
                seconds: self.seconds,
                location: self.location,
            }));
        }
        self.clock.register(cx.waker());
        Poll::Pending
    }
}
