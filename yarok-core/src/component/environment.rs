//! [`Environment`]: where a world runs — `sim`, `real`, `mock`, or one of the user's own.

use super::{Backend, MockBackend};

/// An environment, as a type: its name (selected from config and the command line) and the
/// backend its interfaces bind to.
///
/// yarok's are `Sim` (`yarok-mjc`, MuJoCo), `Real` (`yarok-hw`, devices) and [`Mock`]; a user
/// defines more (`replay`, a co-simulator) with a type of their own. A component lists the
/// environments it supports in [`Component::interfaces`](super::Component::interfaces); the
/// compiler checks that each has an [`Interface`](super::Interface), and the platform checks,
/// before anything is bound, that every component of the world supports the selected one.
pub trait Environment: 'static {
    /// The name it is selected by (`--env NAME`, `environment = "NAME"`); unique per platform.
    const NAME: &'static str;
    /// What its interfaces bind to.
    type Backend: Backend;
}

/// The `mock` environment: no physics, no devices; time advances by a fixed step per tick.
/// For tests of behaviours and plugins.
#[derive(Debug, Clone, Copy)]
pub struct Mock;

impl Environment for Mock {
    const NAME: &'static str = "mock";
    type Backend = MockBackend;
}
