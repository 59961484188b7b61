//! What interfaces register while they bind: per-tick steps, tasks, restart and stop actions,
//! probes, named states and commands, actuations.

use std::future::Future;
use std::pin::Pin;

use super::{NamedActuation, NamedCommand, NamedState, Probe};
use crate::BoxError;

/// A per-tick step an interface registered.
pub(crate) type TickStep = Box<dyn FnMut() -> Result<(), BoxError>>;

/// What puts a component's own state back when the world restarts (an episode begins).
pub(crate) type RestartAction = Box<dyn FnMut()>;

/// Work that runs as a future on the platform's thread.
pub(crate) type LocalFuture = Pin<Box<dyn Future<Output = Result<(), BoxError>>>>;

/// An action that leaves a component safe at shutdown, bounded in time.
pub(crate) struct StopAction {
    pub(crate) component: String,
    pub(crate) seconds: f64,
    pub(crate) action: LocalFuture,
}

/// Everything the bound interfaces registered, in binding order, with the component's path.
#[derive(Default)]
pub(crate) struct Lifecycle {
    pub(crate) ticks: Vec<(String, tracing::Span, TickStep)>,
    pub(crate) tasks: Vec<(String, LocalFuture)>,
    pub(crate) restarts: Vec<RestartAction>,
    pub(crate) stops: Vec<StopAction>,
    pub(crate) probes: Vec<Probe>,
    pub(crate) states: Vec<NamedState>,
    pub(crate) commands: Vec<NamedCommand>,
    pub(crate) actuations: Vec<NamedActuation>,
}
