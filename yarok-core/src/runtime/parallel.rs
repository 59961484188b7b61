//! [`run_parallel`]: many worlds at once, a platform per thread, results in order.

use std::collections::VecDeque;
use std::sync::Mutex;

/// Runs `jobs` on up to `threads` threads at once and returns what each returned, in the jobs'
/// order. A job builds and runs a platform on the thread it is given (platforms are not
/// `Send`): its own world, seed and config overrides. Worlds composed alike share one compiled
/// model (it is never changed; each world has its own data), so an extra world costs little
/// more than its state.
///
/// # Panics
///
/// When a job panics (after the other threads have finished their jobs).
///
/// # Examples
///
/// ```
/// use yarok_core::component::{Component, Declaration, Mock, MockBackend};
/// use yarok_core::runtime::{Platform, run_parallel};
///
/// struct Empty;
/// impl Component for Empty {
///     fn declaration() -> Declaration {
///         Declaration::new("empty").template("<mujoco><worldbody/></mujoco>")
///     }
/// }
///
/// let jobs = (0..4u64).map(|seed| {
///     move || {
///         Platform::builder()
///             .world::<Empty>()
///             .environment("mock")
///             .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
///             .set(&format!("platform/seed={seed}"))?
///             .behaviour(|pl| async move {
///                 pl.wait_seconds(0.1).await?;
///                 Ok(())
///             })
///             .run()?;
///         Ok::<u64, yarok_core::runtime::RuntimeError>(seed)
///     }
/// });
/// let seeds: Vec<u64> = run_parallel(jobs.collect(), 2).into_iter().collect::<Result<_, _>>()?;
/// assert_eq!(seeds, [0, 1, 2, 3]);
/// # Ok::<(), yarok_core::runtime::RuntimeError>(())
/// ```
pub fn run_parallel<T, F>(jobs: Vec<F>, threads: usize) -> Vec<T>
where
    T: Send,
    F: FnOnce() -> T + Send,
{
    let count = jobs.len();
    let queue = Mutex::new(jobs.into_iter().enumerate().collect::<VecDeque<_>>());
    let results = Mutex::new((0..count).map(|_| None).collect::<Vec<Option<T>>>());
    std::thread::scope(|scope| {
        for _ in 0..threads.clamp(1, count.max(1)) {
            scope.spawn(|| {
                loop {
                    let next = queue.lock().unwrap_or_else(|e| e.into_inner()).pop_front();
                    let Some((index, job)) = next else { break };
                    let result = job();
                    results.lock().unwrap_or_else(|e| e.into_inner())[index] = Some(result);
                }
            });
        }
    });
    results
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .map(|result| result.expect("every job ran"))
        .collect()
}
