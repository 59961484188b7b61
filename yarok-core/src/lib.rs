//! yarok-core: everything about a robot that does not depend on where it runs.
//!
//! Its one job is the platform-independent half of yarok: MJCF component templates and their
//! composition into one world, the layered run configuration, the component model, and the
//! single-threaded async runtime on which behaviours `await` platform ticks. It names neither
//! MuJoCo nor any device; simulation lives in `yarok-mjc`, hardware in `yarok-hw`.

pub mod compose;
pub mod config;
pub mod report;
pub mod runtime;
mod stack;
pub mod suggest;
pub mod template;
