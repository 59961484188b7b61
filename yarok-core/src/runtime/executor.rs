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

/// A task that is polled: its future, until it is done, and its waker. Kept apart from what
/// polls do not read ([`TaskInfo`]), so that a tick touches as little memory as it can.
struct Task {
    future: Option<LocalFuture>,
    waker: Waker,
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
    infos: Vec<TaskInfo>,
    wake: Arc<PlatformWake>,
    behaviours: usize,
    clock: Clock,
    /// Whether each task waits for the next tick (by index; dense, so a tick reads little).
    waits_tick: Vec<bool>,
    /// The error a task ended with, until [`Executor::failure`] returns it.
    failed: Option<RuntimeError>,
}

impl Executor {
    pub(crate) fn new(clock: Clock) -> Self {
        Self {
            tasks: Vec::new(),
            infos: Vec::new(),
            wake: Arc::new(PlatformWake {
                any_woken: AtomicBool::new(false),
                sleeping: AtomicBool::new(false),
                notify: Notify::new(),
            }),
            behaviours: 0,
            clock,
            waits_tick: Vec::new(),
            failed: None,
        }
    }

    pub(crate) fn spawn(&mut self, owner: Owner, future: LocalFuture) {
        if matches!(owner, Owner::Behaviour { .. }) {
            self.behaviours += 1;
        }
        let woken = Arc::new(TaskWake {
            woken: AtomicBool::new(true),
            platform: Arc::clone(&self.wake),
        });
        self.wake.any_woken.store(true, Ordering::Release);
        let waker = Waker::from(Arc::clone(&woken));
        self.tasks.push(Task {
            future: Some(future),
            waker,
        });
        self.infos.push(TaskInfo { owner, woken });
        self.waits_tick.push(false);
    }

    /// Whether every behaviour has returned.
    pub(crate) fn behaviours_done(&self) -> bool {
        self.behaviours == 0
    }

    /// After a tick: polls the tasks that waited for it (in the order they were spawned), then
    /// the others woken (see [`Executor::poll`]).
    ///
    /// # Errors
    ///
    /// The first error a behaviour or a component's task returns.
    pub(crate) fn tick(&mut self) -> Result<(), RuntimeError> {
        let mut next = 0;
        while let Some((index, result)) = self.poll_ticked(next) {
            if !self.ended(index, result) {
                return self.failure();
            }
            next = index + 1;
        }
        // Most ticks wake nothing else: a plain load before the call.
        if self.wake.any_woken.load(Ordering::Relaxed) {
            self.poll()?;
        }
        Ok(())
    }

    /// Polls the tasks from `first` on that wait for a tick, until one returns: its index and
    /// result.
    #[inline(always)]
    fn poll_ticked(&mut self, first: usize) -> Option<(usize, Result<(), crate::BoxError>)> {
        let tasks = self.tasks.get_mut(first..)?;
        let waits = self.waits_tick.get_mut(first..)?;
        for (index, (task, waits_tick)) in (first..).zip(tasks.iter_mut().zip(waits)) {
            if *waits_tick && let Some(future) = &mut task.future {
                let mut context = Context::from_waker(&task.waker);
                self.clock.begin_polling(&task.waker);
                let poll = future.as_mut().poll(&mut context);
                *waits_tick = self.clock.end_polling();
                if let Poll::Ready(result) = poll {
                    return Some((index, result));
                }
            }
        }
        None
    }

    /// Polls the tasks woken by anything but a tick until none is (or `MAX_ROUNDS`).
    ///
    /// # Errors
    ///
    /// The first error a behaviour or a component's task returns.
    pub(crate) fn poll(&mut self) -> Result<(), RuntimeError> {
        for _ in 0..MAX_ROUNDS {
            // A plain load first: most ticks wake nothing but tick waits.
            if !self.wake.any_woken.load(Ordering::Relaxed)
                || !self.wake.any_woken.swap(false, Ordering::Acquire)
            {
                break;
            }
            for index in 0..self.tasks.len() {
                // The only consumer clears the flag before polling, so no wake is lost.
                if self.infos[index].woken.woken.swap(false, Ordering::Acquire)
                    && !self.poll_task(index)
                {
                    return self.failure();
                }
            }
        }
        Ok(())
    }

    /// The error a task ended with, once.
    fn failure(&mut self) -> Result<(), RuntimeError> {
        self.failed.take().map_or(Ok(()), Err)
    }

    /// Polls one task; `false` when it failed (its error is kept for [`Executor::failure`]).
    #[inline(always)]
    fn poll_task(&mut self, index: usize) -> bool {
        let Some(Task {
            future: Some(future),
            waker,
        }) = self.tasks.get_mut(index)
        else {
            return true;
        };
        let mut context = Context::from_waker(waker);
        self.clock.begin_polling(waker);
        let poll = future.as_mut().poll(&mut context);
        self.waits_tick[index] = self.clock.end_polling();
        match poll {
            Poll::Pending => true,
            Poll::Ready(result) => self.ended(index, result),
        }
    }

    /// A task returned; `false` when with an error.
    #[cold]
    fn ended(&mut self, index: usize, result: Result<(), crate::BoxError>) -> bool {
        self.tasks[index].future = None;
        let task = &mut self.infos[index];
        if let Owner::Behaviour { .. } = task.owner {
            self.behaviours -= 1;
        }
        let Err(source) = result else {
            return true;
        };
        self.failed = Some(
            match std::mem::replace(&mut task.owner, Owner::Component(String::new())) {
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
        let _results_after_the_end = self.tick();
        self.tasks.clear();
        self.infos.clear();
        self.waits_tick.clear();
        self.behaviours = 0;
    }
}
