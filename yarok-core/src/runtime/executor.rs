//! The platform's executor: polls behaviours and components' tasks on the platform's thread
//! whenever they are woken — by a tick they wait for, or by I/O.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::task::{Context, Poll, Wake, Waker};

use tokio::sync::Notify;
use tokio::time::Instant;

use super::RuntimeError;
use crate::component::LocalFuture;

/// Polling rounds per poll after which tasks that keep waking themselves are left for the next
/// tick.
const MAX_ROUNDS: usize = 1000;

/// Whose a task is: a behaviour (the run lasts while one is pending) or a component's.
pub(crate) enum Owner {
    Behaviour { index: usize, name: String },
    Component(String),
}

struct Task {
    owner: Owner,
    future: LocalFuture,
    woken: Arc<TaskWake>,
    waker: Waker,
    done: bool,
}

/// Set when a task is woken; wakes the platform loop too when it sleeps between paced ticks.
struct TaskWake {
    woken: AtomicBool,
    platform: Arc<PlatformWake>,
}

struct PlatformWake {
    sleeping: AtomicBool,
    notify: Notify,
}

impl Wake for TaskWake {
    fn wake(self: Arc<Self>) {
        self.wake_by_ref();
    }

    fn wake_by_ref(self: &Arc<Self>) {
        self.woken.store(true, Ordering::SeqCst);
        if self.platform.sleeping.load(Ordering::SeqCst) {
            self.platform.notify.notify_one();
        }
    }
}

pub(crate) struct Executor {
    tasks: Vec<Task>,
    wake: Arc<PlatformWake>,
    behaviours: usize,
}

impl Executor {
    pub(crate) fn new() -> Self {
        Self {
            tasks: Vec::new(),
            wake: Arc::new(PlatformWake {
                sleeping: AtomicBool::new(false),
                notify: Notify::new(),
            }),
            behaviours: 0,
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
        let waker = Waker::from(Arc::clone(&woken));
        self.tasks.push(Task {
            owner,
            future,
            woken,
            waker,
            done: false,
        });
    }

    /// Whether every behaviour has returned.
    pub(crate) fn behaviours_done(&self) -> bool {
        self.behaviours == 0
    }

    /// Polls woken tasks until none is woken (or `MAX_ROUNDS`).
    ///
    /// # Errors
    ///
    /// The first error a behaviour or a component's task returns.
    pub(crate) fn poll(&mut self) -> Result<(), RuntimeError> {
        for _ in 0..MAX_ROUNDS {
            let mut progressed = false;
            for task in &mut self.tasks {
                if task.done || !task.woken.woken.swap(false, Ordering::SeqCst) {
                    continue;
                }
                progressed = true;
                let mut context = Context::from_waker(&task.waker);
                if let Poll::Ready(result) = task.future.as_mut().poll(&mut context) {
                    task.done = true;
                    if let Owner::Behaviour { .. } = task.owner {
                        self.behaviours -= 1;
                    }
                    if let Err(source) = result {
                        return Err(
                            match std::mem::replace(
                                &mut task.owner,
                                Owner::Component(String::new()),
                            ) {
                                Owner::Behaviour { index, name } => RuntimeError::Behaviour {
                                    index,
                                    name,
                                    source,
                                },
                                Owner::Component(component) => {
                                    RuntimeError::Interface { component, source }
                                }
                            },
                        );
                    }
                }
            }
            if !progressed {
                break;
            }
        }
        Ok(())
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
            self.wake.sleeping.store(true, Ordering::SeqCst);
            // A wake between this check and the await leaves a permit in `notify`.
            let woken = self
                .tasks
                .iter()
                .any(|t| !t.done && t.woken.woken.load(Ordering::SeqCst));
            if !woken {
                tokio::select! {
                    () = tokio::time::sleep_until(due) => {}
                    () = self.wake.notify.notified() => {}
                }
            }
            self.wake.sleeping.store(false, Ordering::SeqCst);
        }
    }

    /// Gives every task one last poll (their waits now fail with `Stopped`, so they can clean
    /// up), then drops them all.
    pub(crate) fn finish(&mut self) {
        let _results_after_the_end = self.poll();
        self.tasks.clear();
        self.behaviours = 0;
    }
}
