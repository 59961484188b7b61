//! Platform time: the tick clock every wait resolves on.
//!
//! Platform time is simulation time in `sim` and time since start on hardware. A [`Clock`] is
//! shared by the platform (which advances it once per tick) and by everything that waits on it:
//! behaviours through [`Pl`](crate::runtime::Pl), interfaces' tasks through
//! [`Bind::clock`](crate::component::Bind::clock).

mod timeout;
mod wait;

use std::cell::{Cell, RefCell};
use std::future::IntoFuture;
use std::rc::Rc;
use std::task::Waker;

pub use timeout::Timeout;
pub use wait::{Wait, WaitError};

/// The platform's tick clock: cheap to clone, lives on the platform's thread.
#[derive(Clone, Debug)]
pub struct Clock {
    state: Rc<ClockState>,
}

/// Tick state shared by the platform loop and every wait.
#[derive(Debug)]
pub(crate) struct ClockState {
    pub(crate) ticks: Cell<u64>,
    pub(crate) time: Cell<f64>,
    pub(crate) timestep: f64,
    pub(crate) stopped: Cell<bool>,
    waiters: RefCell<Vec<Waker>>,
    /// The other buffer of `waiters`: swapped in at each tick so that neither allocates.
    spare: RefCell<Vec<Waker>>,
    /// The waker identity of the platform's task being polled, so that its waits register by
    /// setting `registered` instead of storing a waker (no reference counting per tick). A wait
    /// polled with another waker registers that waker. While no task is polled: the address of
    /// `registered` ([`ClockState::idle`]), which no waker's data points to.
    polling: Cell<*const ()>,
    /// Whether the task being polled waits for the next tick.
    registered: Cell<bool>,
}

impl ClockState {
    #[inline]
    pub(crate) fn register(&self, waker: &Waker) {
        // Another waker with the same data would have to point into the task's own waker.
        if waker.data() == self.polling.get() {
            self.registered.set(true);
        } else {
            self.register_waker(waker);
        }
    }

    /// What `polling` holds while no task is polled.
    #[inline(always)]
    fn idle(&self) -> *const () {
        std::ptr::from_ref(&self.registered).cast()
    }

    #[cold]
    fn register_waker(&self, waker: &Waker) {
        let mut waiters = self.waiters.borrow_mut();
        // A task polling several waits registers them one after the other; one wake is enough.
        if !waiters.last().is_some_and(|last| last.will_wake(waker)) {
            waiters.push(waker.clone());
        }
    }
}

impl Clock {
    pub(crate) fn new(time: f64, timestep: f64) -> Self {
        let clock = Self {
            state: Rc::new(ClockState {
                ticks: Cell::new(0),
                time: Cell::new(time),
                timestep,
                stopped: Cell::new(false),
                waiters: RefCell::new(Vec::new()),
                spare: RefCell::new(Vec::new()),
                polling: Cell::new(std::ptr::null()),
                registered: Cell::new(false),
            }),
        };
        clock.state.polling.set(clock.state.idle());
        clock
    }

    /// Records a tick and wakes every wait.
    pub(crate) fn advance(&self, time: f64) {
        self.state.ticks.set(self.state.ticks.get() + 1);
        self.state.time.set(time);
        self.wake_all();
    }

    /// Says that the platform's task whose waker is `waker` is being polled.
    #[inline(always)]
    pub(crate) fn begin_polling(&self, waker: &Waker) {
        self.state.registered.set(false);
        self.state.polling.set(waker.data());
    }

    /// Says that the poll is over; returns whether the task waits for the next tick.
    #[inline(always)]
    pub(crate) fn end_polling(&self) -> bool {
        self.state.polling.set(self.state.idle());
        self.state.registered.get()
    }

    /// Makes every pending and future wait fail with [`WaitError::Stopped`].
    pub(crate) fn stop(&self) {
        self.state.stopped.set(true);
        self.wake_all();
    }

    #[inline]
    fn wake_all(&self) {
        if !self.state.waiters.borrow().is_empty() {
            self.wake_waiters();
        }
    }

    #[cold]
    fn wake_waiters(&self) {
        // Waking may register new waits: wake from the other buffer.
        let mut waking = self.state.spare.take();
        std::mem::swap(&mut waking, &mut *self.state.waiters.borrow_mut());
        for waker in waking.drain(..) {
            waker.wake();
        }
        *self.state.spare.borrow_mut() = waking;
    }

    /// Platform time in seconds: simulation time in `sim`, time since start on hardware.
    pub fn time(&self) -> f64 {
        self.state.time.get()
    }

    /// Ticks since start.
    pub fn ticks(&self) -> u64 {
        self.state.ticks.get()
    }

    /// Seconds per tick.
    pub fn timestep(&self) -> f64 {
        self.state.timestep
    }

    /// Resolves on the first tick after which `condition` holds; it is checked after every
    /// tick, and at least one tick passes.
    ///
    /// # Cancel safety
    ///
    /// Cancel safe: dropping the wait changes nothing.
    #[track_caller]
    pub fn wait<C: FnMut() -> bool + Unpin>(&self, condition: C) -> Wait<'_, C> {
        Wait::new(&self.state, condition)
    }

    /// Resolves once `seconds` of platform time have passed (to the nearest tick).
    /// `f64::INFINITY` waits forever; NaN or a negative number makes the wait fail at once with
    /// [`WaitError::InvalidDuration`].
    ///
    /// # Cancel safety
    ///
    /// Cancel safe.
    #[track_caller]
    pub fn wait_seconds(&self, seconds: f64) -> Wait<'_, impl FnMut() -> bool + Unpin + '_> {
        let state = &*self.state;
        let target = state.time.get() + seconds - state.timestep / 2.0;
        Wait::new(state, move || state.time.get() >= target)
            .invalid(WaitError::check_duration("wait_seconds", seconds))
    }

    /// Resolves after the next tick.
    ///
    /// # Cancel safety
    ///
    /// Cancel safe.
    #[track_caller]
    pub fn tick(&self) -> Wait<'_, impl FnMut() -> bool + Unpin> {
        Wait::new(&self.state, || true)
    }

    /// Never resolves on its own; ends with an error when the platform stops (or its timeout).
    ///
    /// # Cancel safety
    ///
    /// Cancel safe.
    #[track_caller]
    pub fn wait_forever(&self) -> Wait<'_, impl FnMut() -> bool + Unpin> {
        Wait::new(&self.state, || false)
    }

    /// Runs `future` with a deadline `seconds` of platform time away: its output, or
    /// [`WaitError::Timeout`] if the deadline passes first (the future is then dropped).
    /// NaN or a negative number fails at once with [`WaitError::InvalidDuration`].
    ///
    /// Any future works (or anything `.await` takes: an arm's motion) — a channel receive, a socket read, several waits joined — and, unlike
    /// `tokio::time::timeout`, its deadline is in platform time, so it means the same in `sim`
    /// (simulated seconds) as on hardware.
    ///
    /// # Cancel safety
    ///
    /// As cancel safe as `future`.
    #[track_caller]
    pub fn timeout<F: IntoFuture>(&self, seconds: f64, future: F) -> Timeout<'_, F::IntoFuture> {
        Timeout::new(&self.state, seconds, future.into_future())
    }
}
