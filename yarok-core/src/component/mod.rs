//! The component model: what a component is and how it binds to an environment.
//!
//! A component is a Rust type implementing [`Component`]: its [`Declaration`] says what it is
//! in MJCF (tag, template, defaults, sub-components), and [`Component::interfaces`] lists the
//! [environments](Environment) it runs in, each an [`Interface`] implementation the compiler
//! checks. At start-up the platform [binds](Bind) every component to the selected environment's
//! [`Backend`]; the component's value is then the handle behaviours get with `pl.get(path)`.
//!
//! # Examples
//!
//! A counter that works in `mock` and in a user-defined `replay` environment:
//!
//! ```
//! use yarok_core::component::{
//!     Backend, Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, Mock,
//!     MockBackend,
//! };
//!
//! /// Replays recorded data (here: nothing but time).
//! struct Replay;
//! impl Environment for Replay {
//!     const NAME: &'static str = "replay";
//!     type Backend = MockBackend;
//! }
//!
//! #[derive(Clone, serde::Serialize, serde::Deserialize)]
//! struct Counter { start: u32 }
//!
//! impl Component for Counter {
//!     fn declaration() -> Declaration {
//!         Declaration::new("counter").config(Counter { start: 3 })
//!     }
//!     fn interfaces(interfaces: &mut Interfaces<Self>) {
//!         interfaces.add::<Mock>().add::<Replay>();
//!     }
//! }
//!
//! impl Interface<Mock> for Counter {
//!     async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
//!         bind.config()
//!     }
//! }
//!
//! impl Interface<Replay> for Counter {
//!     async fn bind(_: &mut Bind<Replay>) -> Result<Self, BindError> {
//!         Ok(Counter { start: 0 })
//!     }
//! }
//!
//! let counter = yarok_core::component::ComponentType::of::<Counter>();
//! assert_eq!(counter.environments(), ["mock", "replay"]);
//! ```

mod actuation;
mod backend;
mod bind;
mod command;
mod declaration;
mod environment;
mod handles;
mod interface;
mod lifecycle;
mod named;
mod names;
mod probe;
mod state;

use std::any::TypeId;
use std::fmt;

pub use actuation::{Actuators, NamedActuation};
pub use backend::{Backend, MockBackend};
pub(crate) use bind::BindContext;
pub use bind::{Bind, BindError, DEFAULT_STOP_SECONDS};
pub use command::NamedCommand;
pub use declaration::Declaration;
pub(crate) use declaration::Source;
pub use environment::{Environment, Mock};
pub use handles::HandleError;
pub(crate) use handles::Handles;
pub(crate) use interface::Binder;
pub use interface::{Interface, Interfaces};
pub(crate) use lifecycle::{Lifecycle, LocalFuture, StopAction, TickStep};
pub use named::Named;
pub use names::{NameKind, NameMap};
pub use probe::{Probe, ProbeImage};
pub use state::NamedState;

/// A component: a Rust type with an MJCF template and an interface per environment it runs in.
///
/// # Examples
///
/// ```
/// use yarok_core::component::{Component, Declaration};
/// use yarok_core::compose::compose;
///
/// struct Block;
/// impl Component for Block {
///     fn declaration() -> Declaration {
///         Declaration::new("block")
///             .default("size", 0.05)
///             .template(r#"<mujoco><worldbody>
///                 <body name="body"><freejoint/><geom type="box" size="{size} {size} {size}"/></body>
///             </worldbody></mujoco>"#)
///     }
/// }
///
/// struct Table;
/// impl Component for Table {
///     fn declaration() -> Declaration {
///         Declaration::new("table").uses::<Block>().template(r#"<mujoco><worldbody>
///             <for each="range(2)" as="i">
///               <body name="spot{i}" pos="{i * 0.2} 0 0.5"><block name="block{i}" size="0.03"/></body>
///             </for>
///         </worldbody></mujoco>"#)
///     }
/// }
///
/// let world = compose::<Table>()?;
/// let xml = world.to_xml();
/// assert!(xml.contains(r#"<body name="block1/body">"#));
/// assert!(xml.contains(r#"size="0.03 0.03 0.03""#));
/// assert_eq!(world.instance("/block0").unwrap().names.len(), 1);
/// # Ok::<(), yarok_core::compose::ComposeError>(())
/// ```
pub trait Component: Sized + 'static {
    /// What the component is: tag, template, defaults, sub-components.
    fn declaration() -> Declaration;

    /// The environments the component runs in: `interfaces.add::<Sim>().add::<Mock>()`, each
    /// an [`Interface`] implementation. The default lists none: a world or a prop, which has
    /// nothing to bind and runs anywhere.
    fn interfaces(_interfaces: &mut Interfaces<Self>) {}

    /// The name messages give the component's type: its Rust type's by default. A generic
    /// component names itself as users know it (`Ur5e` rather than `UrArm<Ur5eModel>`).
    fn type_name() -> &'static str {
        std::any::type_name::<Self>()
    }
}

/// A component type, as a value.
#[derive(Clone, Copy)]
pub struct ComponentType {
    type_id: TypeId,
    type_name: &'static str,
    declaration: fn() -> Declaration,
    interfaces: fn() -> interface::Filled,
}

impl ComponentType {
    /// The component type `C`.
    pub fn of<C: Component>() -> Self {
        Self {
            type_id: TypeId::of::<C>(),
            type_name: C::type_name(),
            declaration: C::declaration,
            interfaces: || {
                let mut interfaces = Interfaces::<C>::new();
                C::interfaces(&mut interfaces);
                interfaces.filled()
            },
        }
    }

    /// The Rust type's name.
    pub fn type_name(&self) -> &'static str {
        self.type_name
    }

    /// The `TypeId` of the component's Rust type.
    pub fn type_id(&self) -> TypeId {
        self.type_id
    }

    /// The component's declaration.
    pub fn declaration(&self) -> Declaration {
        (self.declaration)()
    }

    /// The names of the environments it has an interface for, in the order it lists them.
    pub fn environments(&self) -> Vec<&'static str> {
        (self.interfaces)()
            .entries
            .into_iter()
            .map(|(name, _)| name)
            .collect()
    }

    /// What would add its interface for `environment` if this build leaves it out (see
    /// [`Interfaces::unavailable`]).
    pub fn unavailable(&self, environment: &str) -> Option<&'static str> {
        (self.interfaces)()
            .unavailable
            .into_iter()
            .find(|(name, _)| *name == environment)
            .map(|(_, what)| what)
    }

    /// Its interface for `environment`.
    pub(crate) fn binder(&self, environment: &str) -> Option<Binder> {
        (self.interfaces)()
            .entries
            .into_iter()
            .find(|(name, _)| *name == environment)
            .map(|(_, bind)| bind)
    }

    pub(crate) fn with_name(self, type_name: &'static str) -> Self {
        Self { type_name, ..self }
    }
}

impl fmt::Debug for ComponentType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.type_name)
    }
}
