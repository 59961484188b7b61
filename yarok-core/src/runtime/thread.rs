//! [`PlatformThread`]: a platform on a thread of its own, for multi-threaded applications.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use tokio::sync::oneshot;

use super::{PlatformBuilder, RuntimeError};

/// A platform running on its own thread (its GL context and `!Send` handles stay there),
/// controlled from anywhere through this `Send` handle.
///
/// # Examples
///
/// ```
/// use yarok_core::component::{Component, Declaration, Mock, MockBackend};
/// use yarok_core::runtime::{Platform, PlatformThread};
///
/// struct Empty;
/// impl Component for Empty {
///     fn declaration() -> Declaration {
///         Declaration::new("empty").template("<mujoco><worldbody/></mujoco>")
///     }
/// }
///
/// let running = PlatformThread::spawn(|| {
///     Platform::builder()
///         .world::<Empty>()
///         .environment("mock")
///         .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
///         .behaviour(|pl| async move {
///             pl.wait_forever().await?;
///             Ok(())
///         })
/// });
/// running.stop();
/// running.join()?;
/// # Ok::<(), yarok_core::runtime::RuntimeError>(())
/// ```
#[derive(Debug)]
pub struct PlatformThread {
    stop: Arc<AtomicBool>,
    done: oneshot::Receiver<Result<(), RuntimeError>>,
}

impl PlatformThread {
    /// Starts a thread that builds the platform `make` describes and runs it.
    ///
    /// # Panics
    ///
    /// When the operating system cannot start a thread.
    pub fn spawn(make: impl FnOnce() -> PlatformBuilder + Send + 'static) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let (sender, done) = oneshot::channel();
        std::thread::Builder::new()
            .name("yarok-platform".into())
            .spawn(move || {
                let result = make()
                    .stop_flag(flag)
                    .build()
                    .and_then(super::Platform::run);
                let _receiver_may_be_gone = sender.send(result);
            })
            .expect("the operating system could not start the platform thread");
        Self { stop, done }
    }

    /// Asks the platform to stop after its current tick.
    pub fn stop(&self) {
        self.stop.store(true, Ordering::Relaxed);
    }

    /// Waits, asynchronously, for the platform to end and returns how it ended.
    ///
    /// # Errors
    ///
    /// The platform's error, or [`RuntimeError::ThreadDied`] if its thread panicked.
    ///
    /// # Cancel safety
    ///
    /// Not cancel safe: the result is lost if the future is dropped (the platform runs on).
    pub async fn finished(self) -> Result<(), RuntimeError> {
        self.done.await.unwrap_or(Err(RuntimeError::ThreadDied))
    }

    /// Blocks until the platform ends; for code outside async contexts.
    ///
    /// # Errors
    ///
    /// As [`PlatformThread::finished`].
    pub fn join(self) -> Result<(), RuntimeError> {
        self.done
            .blocking_recv()
            .unwrap_or(Err(RuntimeError::ThreadDied))
    }
}
