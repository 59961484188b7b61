//! The platform's executor: polls behaviours and components' tasks on the platform's thread
//! whenever they are woken — by a tick they wait for, or by I/O.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::task::{Context, Poll, Wake, Waker};

use tokio::sync::Notify;
use tokio::time::Instant;

use super::RuntimeError;
use crate::component::LocalFuture;
use crate::time::Clock;

/// Polling rounds per poll after which tasks that keep waking themselves are left for the next
/// tick.
const MAX_ROUNDS: usize = 1000;

/// Whose a task is: a behaviour (the run lasts while one is pending) or a component's.
pub(crate) enum Owner {
    Behaviour { index: usize, name: String },
    Component(String),
}

/// A task that is polled: its future (a never-ready one once it is done), its waker, and
/// whether it waits for the next tick. Kept apart from what polls do not read ([`TaskInfo`]),
/// so that a tick touches as little memory as it can.
struct Task {
    future: LocalFuture,
    waker: Waker,
    waits_tick: bool,
}

impl Task {
    /// Polls the future, and notes whether it now waits for the next tick.
    #[inline(always)]
    fn poll(&mut self, clock: &Clock) -> Poll<Result<(), crate::BoxError>> {
        let mut context = Context::from_waker(&self.waker);
        clock.begin_polling(&self.waker);
        let poll = self.future.as_mut().poll(&mut context);
        self.waits_tick = clock.end_polling();
        poll
    }
}

/// Whose a task is, and the flag its waker sets.
struct TaskInfo {
    owner: Owner,
    woken: Arc<TaskWake>,
}

/// Set when a task is woken by anything but a tick (I/O, a channel, another task); wakes the
/// platform loop too when it sleeps between paced ticks.
struct TaskWake {
    woken: AtomicBool,
    platform: Arc<PlatformWake>,
}

struct PlatformWake {
    /// Some task's `woken` was set since the executor last looked.
    any_woken: AtomicBool,
    sleeping: AtomicBool,
    notify: Notify,
}

impl Wake for TaskWake {
    fn wake(self: Arc<Self>) {
        self.wake_by_ref();
    }

    fn wake_by_ref(self: &Arc<Self>) {
        // Ticks and tokio's I/O wake tasks on the platform's thread, in program order with its
        // `sleeping`. A wake from another thread racing the platform's falling asleep is seen at
        // the next tick at the latest: no stronger (and costlier) ordering is needed for that.
        self.woken.store(true, Ordering::Release);
        self.platform.any_woken.store(true, Ordering::Release);
        if self.platform.sleeping.load(Ordering::Acquire) {
            self.platform.notify.notify_one();
        }
    }
}

pub(crate) struct Executor {
    tasks: Vec<Task>,
    ledger: Ledger,
    wake: Arc<PlatformWake>,
    clock: Clock,
}

/// What the executor keeps of its tasks besides polling them: whose each is, how many
/// behaviours are pending, and the error a task ended with.
struct Ledger {
    infos: Vec<TaskInfo>,
    behaviours: usize,
    /// The error a task ended with, until [`Executor::failure`] returns it.
    failed: Option<RuntimeError>,
}

impl Executor {
    pub(crate) fn new(clock: Clock) -> Self {
        Self {
            tasks: Vec::new(),
            ledger: Ledger {
                infos: Vec::new(),
                behaviours: 0,
                failed: None,
            },
            wake: Arc::new(PlatformWake {
                any_woken: AtomicBool::new(false),
                sleeping: AtomicBool::new(false),
                notify: Notify::new(),
            }),
            clock,
        }
    }

    pub(crate) fn spawn(&mut self, owner: Owner, future: LocalFuture) {
        if matches!(owner, Owner::Behaviour { .. }) {
            self.ledger.behaviours += 1;
        }
        let woken = Arc::new(TaskWake {
            woken: AtomicBool::new(true),
            platform: Arc::clone(&self.wake),
        });
        self.wake.any_woken.store(true, Ordering::Release);
        let waker = Waker::from(Arc::clone(&woken));
        self.tasks.push(Task {
            future,
            waker,
            waits_tick: false,
        });
        self.ledger.infos.push(TaskInfo { owner, woken });
    }

    /// Whether every behaviour has returned.
    pub(crate) fn behaviours_done(&self) -> bool {
        self.ledger.behaviours == 0
    }

    /// After a tick: polls the tasks that waited for it (in the order they were spawned), then
    /// the others woken (see [`Executor::poll`]); `false` when a behaviour or a component's task
    /// failed ([`Executor::failure`] has its error).
    #[inline(always)]
    pub(crate) fn tick(&mut self) -> bool {
        for (index, task) in self.tasks.iter_mut().enumerate() {
            if task.waits_tick
                && let Poll::Ready(result) = task.poll(&self.clock)
                && !self.ledger.ended(task, index, result)
            {
                return false;
            }
        }
        // Most ticks wake nothing else: a plain load before the call.
        !self.wake.any_woken.load(Ordering::Relaxed) || self.poll_woken()
    }

    /// Polls the tasks woken by anything but a tick until none is (or `MAX_ROUNDS`).
    ///
    /// # Errors
    ///
    /// The first error a behaviour or a component's task returns.
    pub(crate) fn poll(&mut self) -> Result<(), RuntimeError> {
        if self.poll_woken() {
            Ok(())
        } else {
            self.failure()
        }
    }

    /// [`Executor::poll`]; `false` when a task failed.
    #[inline(never)]
    fn poll_woken(&mut self) -> bool {
        for _ in 0..MAX_ROUNDS {
            // A plain load first: most ticks wake nothing but tick waits.
            if !self.wake.any_woken.load(Ordering::Relaxed)
                || !self.wake.any_woken.swap(false, Ordering::Acquire)
            {
                break;
            }
            for index in 0..self.tasks.len() {
                // The only consumer clears the flag before polling, so no wake is lost.
                if self.ledger.infos[index]
                    .woken
                    .woken
                    .swap(false, Ordering::Acquire)
                    && !self.poll_task(index)
                {
                    return false;
                }
            }
        }
        true
    }

    /// The error a task ended with, once (after a poll said one failed).
    ///
    /// # Errors
    ///
    /// That error.
    #[cold]
    pub(crate) fn failure(&mut self) -> Result<(), RuntimeError> {
        self.ledger.failed.take().map_or(Ok(()), Err)
    }

    /// Polls one task; `false` when it failed (its error is kept for [`Executor::failure`]).
    #[inline(always)]
    fn poll_task(&mut self, index: usize) -> bool {
        let Some(task) = self.tasks.get_mut(index) else {
            return true;
        };
        match task.poll(&self.clock) {
            Poll::Pending => true,
            Poll::Ready(result) => self.ledger.ended(task, index, result),
        }
    }

    /// Serves wake-ups (I/O reaching tasks at once) until `due`, or until the behaviours are
    /// done.
    ///
    /// # Errors
    ///
    /// As [`Executor::poll`].
    pub(crate) async fn serve_until(&mut self, due: Instant) -> Result<(), RuntimeError> {
        loop {
            self.poll()?;
            if Instant::now() >= due || self.behaviours_done() {
                return Ok(());
            }
            self.wake.sleeping.store(true, Ordering::Release);
            // A wake between this check and the await leaves a permit in `notify`.
            if !self.wake.any_woken.load(Ordering::Acquire) {
                tokio::select! {
                    () = tokio::time::sleep_until(due) => {}
                    () = self.wake.notify.notified() => {}
                }
            }
            self.wake.sleeping.store(false, Ordering::Release);
        }
    }

    /// Gives every waiting task one last poll (call it once the clock has stopped: their waits
    /// then fail with `Stopped`, so they can clean up), then drops them all.
    pub(crate) fn finish(&mut self) {
        // What the tasks return now does not change the run's result.
        self.tick();
        self.ledger.failed = None;
        self.tasks.clear();
        self.ledger.infos.clear();
        self.ledger.behaviours = 0;
    }
}

impl Ledger {
    /// `task`, the one at `index`, returned `result`: it is not polled again; `false` when it
    /// returned an error.
    #[cold]
    fn ended(
        &mut self,
        task: &mut Task,
        index: usize,
        result: Result<(), crate::BoxError>,
    ) -> bool {
        task.future = Box::pin(std::future::pending());
        let info = &mut self.infos[index];
        if let Owner::Behaviour { .. } = info.owner {
            self.behaviours -= 1;
        }
        let Err(source) = result else {
            return true;
        };
        self.failed = Some(
            match std::mem::replace(&mut info.owner, Owner::Component(String::new())) {
                Owner::Behaviour { index, name } => RuntimeError::Behaviour {
                    index,
                    name,
                    source,
                },
                Owner::Component(component) => RuntimeError::Interface { component, source },
            },
        );
        false
    }
}
