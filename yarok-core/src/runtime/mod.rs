//! The runtime: a [`Platform`] composes the world, binds each component to the selected
//! environment's [`Backend`], then ticks — backend step, interfaces' steps (children before
//! parents), plugins' steps, then every behaviour woken by the tick runs until it waits again.
//!
//! Behaviours are `async` functions that receive a [`Pl`]: `pl.wait(cond)`, `pl.wait_seconds(s)`,
//! `pl.tick()` and `pl.wait_forever()` resolve on ticks, in platform time (simulation time in
//! `sim`), so a simulated run is deterministic and as fast as the machine allows.
//!
//! # Examples
//!
//! ```
//! use yarok_core::compose::{Component, Declaration};
//! use yarok_core::runtime::{MockBackend, Platform};
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
//!     .backend("sim", |_, _| Ok(Box::new(MockBackend::new(0.01, false))))
//!     .behaviour(|pl| async move {
//!         pl.wait_seconds(1.0).await?;
//!         assert_eq!(pl.ticks(), 100);
//!         Ok(())
//!     })
//!     .run()?;
//! # Ok::<(), yarok_core::runtime::RuntimeError>(())
//! ```

mod backend;
mod bind;
mod interrupt;
mod platform;
mod plugin;
mod thread;
mod wait;

pub use backend::{Backend, BackendFactory, MockBackend};
pub use bind::Bind;
pub use platform::{BehaviourResult, Pl, Platform, PlatformBuilder};
pub use plugin::Plugin;
pub use thread::PlatformThread;
pub use wait::{Wait, WaitError};

use crate::compose::ComposeError;
use crate::config::ConfigError;

/// Errors of behaviours, plugins and interfaces: anything that can be sent across threads.
pub type BoxError = Box<dyn std::error::Error + Send + Sync>;

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
    /// A component has no interface for the selected environment.
    #[error("component {component} has no `{environment}` interface")]
    NoInterface {
        /// The component's path.
        component: String,
        /// The selected environment.
        environment: String,
    },
    /// A component has no run-time interface at all (a world, a prop).
    #[error("component {path} has no run-time interface")]
    NoHandle {
        /// The component's path.
        path: String,
    },
    /// A component could not bind to the backend.
    #[error("component {component}: {message}")]
    Bind {
        /// The component's path.
        component: String,
        /// What went wrong.
        message: String,
    },
    /// No component has this path.
    #[error("no component at {path}{hint}")]
    NoComponent {
        /// The path asked for.
        path: String,
        /// A "did you mean" suggestion, or nothing.
        hint: String,
    },
    /// A component name matches several paths.
    #[error("`{name}` names several components ({paths}); use a path")]
    Ambiguous {
        /// The name asked for.
        name: String,
        /// The paths it matches.
        paths: String,
    },
    /// The component at a path is another type than asked for.
    #[error("{path} is a {found}, not a {expected}")]
    WrongType {
        /// The path asked for.
        path: String,
        /// The type asked for.
        expected: &'static str,
        /// The component's type.
        found: &'static str,
    },
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
    /// An interface's per-tick step failed.
    #[error("component {component}: {source}")]
    Interface {
        /// The component's path.
        component: String,
        /// Its error.
        source: BoxError,
    },
    /// The backend failed.
    #[error("backend: {0}")]
    Backend(String),
    /// Ctrl-C.
    #[error("interrupted")]
    Interrupted,
}
