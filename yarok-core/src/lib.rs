//! yarok-core: everything about a robot that does not depend on where it runs.
//!
//! Its one job is the platform-independent half of yarok. Its modules stand on each other in
//! one direction:
//!
//! - the floor: [`value`] (config values), [`config`] (the layered run configuration),
//!   [`time`] (platform time and waits) and [`component`] (the component model: components,
//!   environments, interfaces, binding, backends);
//! - [`template`] and [`compose`]: MJCF component templates and their composition into one world;
//! - [`runtime`]: the platform that binds components and runs behaviours and plugins on ticks;
//! - beside them, [`output`]: the rule every writer follows (a file is replaced only when yarok
//!   wrote it), and [`output_file`]: the one way the library writes a file.
//!
//! It names neither MuJoCo nor any device; simulation lives in `yarok-mjc`, hardware in
//! `yarok-hw`.

pub mod args;
pub mod bounded;
pub mod component;
pub mod compose;
pub mod config;
pub mod output;
mod output_error;
pub mod output_file;
pub mod output_lock;
pub use output_error::OutputError;
pub mod report;
pub mod runtime;
mod stack;
pub mod stdout;
pub mod suggest;
pub mod template;
pub mod time;
pub mod value;

/// Errors of behaviours, plugins and interfaces: anything that can be sent across threads.
pub type BoxError = Box<dyn std::error::Error + Send + Sync>;
