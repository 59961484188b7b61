//! The runtime: a [`Platform`] composes the world, binds each component to the selected
//! environment's backend, then ticks — backend step, components' per-tick steps (children before
//! parents), plugins' steps, then every behaviour and task woken by the tick runs until it waits
//! again.
//!
//! Behaviours are `async` functions that receive a [`Pl`]: `pl.wait(cond)`, `pl.wait_seconds(s)`,
//! `pl.tick()`, `pl.timeout(s, future)` and `pl.wait_forever()` resolve on ticks, in platform
//! time (simulation time in `sim`), so a simulated run is deterministic and as fast as the
//! machine allows.
//!
//! # Examples
//!
//! ```
//! use yarok_core::component::{Component, Declaration, Mock, MockBackend};
//! use yarok_core::runtime::Platform;
//!
//! struct Empty;
//! impl Component for Empty {
//!     fn declaration() -> Declaration {
//!         Declaration::new("empty").template("<mujoco><worldbody/></mujoco>")
//!     }
//! }
//!
//! Platform::builder()
//!     .world::<Empty>()
//!     .environment("mock")
//!     .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
//!     .behaviour(|pl| async move {
//!         pl.wait_seconds(1.0).await?;
//!         assert_eq!(pl.ticks(), 100);
//!         Ok(())
//!     })
//!     .run()?;
//! # Ok::<(), yarok_core::runtime::RuntimeError>(())
//! ```

mod builder;
mod episode;
mod executor;
mod interrupt;
mod parallel;
mod pl;
mod platform;
mod plugin;
mod thread;

pub use builder::PlatformBuilder;
pub use episode::{Episode, EpisodeError, Happening};
pub use parallel::run_parallel;
pub use pl::{LogLine, Pl};
pub use platform::Platform;
pub use plugin::{Plugin, World};
pub use thread::PlatformThread;

use crate::BoxError;
use crate::component::BindError;
use crate::compose::ComposeError;
use crate::config::ConfigError;

/// What a behaviour returns.
pub type BehaviourResult = Result<(), BoxError>;

crate::debug_as_report!(RuntimeError);

/// What stopped a platform from starting or running.
#[derive(thiserror::Error)]
#[non_exhaustive]
pub enum RuntimeError {
    /// The builder was given no world.
    #[error("no world: call `world::<W>()` on the builder")]
    NoWorld,
    /// The world could not be composed.
    #[error(transparent)]
    Compose(#[from] ComposeError),
    /// The run configuration is wrong.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// No backend is registered for the selected environment.
    #[error("no backend for environment `{environment}` (available: {available})")]
    NoBackend {
        /// The selected environment.
        environment: String,
        /// The registered ones.
        available: String,
    },
    /// Components of the world have no interface for the selected environment; nothing was
    /// started.
    #[error("{} cannot run in `{environment}`: {}", if .components.len() == 1 { "a component" } else { "components" }, unsupported(.components))]
    Unsupported {
        /// The selected environment.
        environment: String,
        /// Each component that cannot run in it (path and Rust type), with the environments it
        /// supports.
        components: Vec<Unsupported>,
    },
    /// A plugin does not run in the selected environment; nothing was started.
    #[error("plugin {plugin} cannot run in `{environment}`: it runs in {}", .supports.join(", "))]
    PluginUnsupported {
        /// The plugin's name.
        plugin: String,
        /// The selected environment.
        environment: String,
        /// The environments it runs in.
        supports: Vec<&'static str>,
    },
    /// The selected environment's backend could not be made.
    #[error("the `{environment}` backend could not start: {source}")]
    Backend {
        /// The selected environment.
        environment: String,
        /// Why.
        source: BoxError,
    },
    /// The backend failed while stepping.
    #[error("the `{environment}` backend failed: {source}")]
    Step {
        /// The selected environment.
        environment: String,
        /// Why.
        source: BoxError,
    },
    /// A component could not bind.
    #[error(transparent)]
    Bind(#[from] BindError),
    /// A behaviour returned an error.
    #[error("behaviour {name} failed: {source}")]
    Behaviour {
        /// Which behaviour (in the order added).
        index: usize,
        /// Its function's name, where it was added, or its label.
        name: String,
        /// Its error.
        source: BoxError,
    },
    /// A plugin failed.
    #[error("plugin {name} failed: {source}")]
    Plugin {
        /// The plugin's name.
        name: String,
        /// Its error.
        source: BoxError,
    },
    /// A component's per-tick step or task failed.
    #[error("component {component}: {source}")]
    Interface {
        /// The component's path.
        component: String,
        /// Its error.
        source: BoxError,
    },
    /// A component's stop action failed or ran out of time (the others still ran).
    #[error("component {component} did not stop cleanly: {source}")]
    Stop {
        /// The component's path.
        component: String,
        /// Its error.
        source: BoxError,
    },
    /// The tokio runtime could not start.
    #[error("cannot start the platform's tokio runtime: {0}")]
    Start(#[source] std::io::Error),
    /// The platform's thread ended without a result (it panicked).
    #[error("the platform thread died without a result")]
    ThreadDied,
    /// A signal asked the platform to stop: Ctrl-C (`SIGINT`), `SIGTERM` or `SIGHUP`.
    #[error("interrupted by {}", signal_name(*signal))]
    Interrupted {
        /// The signal's number.
        signal: i32,
    },
}

/// The name of a signal that stops the platform.
fn signal_name(signal: i32) -> String {
    match signal {
        signal_hook::consts::SIGINT => "Ctrl-C (SIGINT)".into(),
        signal_hook::consts::SIGTERM => "SIGTERM".into(),
        signal_hook::consts::SIGHUP => "SIGHUP".into(),
        other => format!("signal {other}"),
    }
}

/// A component that cannot run in the selected environment.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unsupported {
    /// Its path.
    pub path: String,
    /// Its Rust type.
    pub type_name: &'static str,
    /// The environments it supports.
    pub supports: Vec<&'static str>,
    /// What would add its interface for the selected environment, if this build leaves it out
    /// (a cargo feature).
    pub added_by: Option<&'static str>,
}

fn unsupported(components: &[Unsupported]) -> String {
    components
        .iter()
        .map(|c| {
            let short = c.type_name.rsplit("::").next().unwrap_or(c.type_name);
            let added = c
                .added_by
                .map(|what| format!(" — build yarok with {what} to run it here"))
                .unwrap_or_default();
            format!(
                "{} ({short}) supports {}{added}",
                c.path,
                c.supports.join(", ")
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}
