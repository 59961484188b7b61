//! yarok: compose robots and robotic environments from reusable MJCF components, simulate them in
//! MuJoCo, and run the same async behaviour code on real hardware.
//!
//! This facade re-exports the workspace crates:
//!
//! - [`core`] (`yarok-core`): templates, composition, config and the async runtime;
//! - [`mjc`] (`yarok-mjc`): MuJoCo bindings, safe model/data, headless rendering;
//! - [`hw`] (`yarok-hw`): the `real` environment and the device drivers (UR, Robotiq,
//!   Marlin printers, cameras);
//! - [`components`] (`yarok-components`): the bundled components.
//!
//! # Cargo features
//!
//! - `render` (default): offscreen camera rendering through EGL (see [`mjc::Renderer`]).
//! - `zenoh`: the Zenoh bridge (`components::plugins::ZenohBridge`; `yarok run WORLD --bridge`).
//! - `viewer`: the viewer and inspector windows on X11 (`components::plugins::Viewer`,
//!   `components::plugins::Inspector`; `yarok run WORLD --viewer --inspect`).
//!
//! # The project's README
//!
#![doc = include_str!("../README.md")]

/// The book's chapters (`docs/src`): their Rust examples run as doc tests.
#[cfg(doctest)]
mod book {
    #[doc = include_str!("../docs/src/python.md")]
    mod python {}
    #[doc = include_str!("../docs/src/learning.md")]
    mod learning {}
    #[doc = include_str!("../docs/src/components.md")]
    mod components {}
    #[doc = include_str!("../docs/src/own-crate.md")]
    mod own_crate {}
    #[doc = include_str!("../docs/src/first-component.md")]
    mod first_component {}
    #[doc = include_str!("../docs/src/motion.md")]
    mod motion {}
    #[doc = include_str!("../docs/src/hardware.md")]
    mod hardware {}
    #[doc = include_str!("../docs/src/plugins.md")]
    mod plugins {}
    #[doc = include_str!("../docs/src/testing.md")]
    mod testing {}
    #[doc = include_str!("../docs/src/cameras.md")]
    mod cameras {}
    #[doc = include_str!("../docs/src/tactile.md")]
    mod tactile {}
    #[doc = include_str!("../docs/src/worlds.md")]
    mod worlds {}
    #[doc = include_str!("../docs/src/many-worlds.md")]
    mod many_worlds {}
}

use yarok_core::component::{Mock, MockBackend};
use yarok_core::runtime::{Platform, PlatformBuilder};

#[doc(inline)]
pub use yarok_components as components;
/// Linear algebra for poses (`Isometry3`) and kinematics.
pub use yarok_components::nalgebra;
#[doc(inline)]
pub use yarok_core as core;
#[doc(inline)]
pub use yarok_hw as hw;
#[doc(inline)]
pub use yarok_mjc as mjc;

pub use yarok_core::BoxError;
pub use yarok_core::component::{Component, Declaration};
pub use yarok_core::runtime::{BehaviourResult, Pl, Plugin, RuntimeError, World};
pub use yarok_core::time::WaitError;

/// What writing components and behaviours needs, in one `use yarok::prelude::*;`.
pub mod prelude {
    pub use yarok_core::BoxError;
    pub use yarok_core::component::{
        Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, Mock,
    };
    pub use yarok_core::runtime::{BehaviourResult, Pl, Plugin, World};
    pub use yarok_core::time::{Clock, WaitError};
    pub use yarok_hw::Real;
    pub use yarok_mjc::{Actuator, Body, Joint, Sensor, Sim, SimBind, Site};
}

/// Seconds per tick of the `mock` environment.
pub const MOCK_TIMESTEP: f64 = 0.002;

/// A platform builder with yarok's environments and plugins registered: environments `sim`
/// (MuJoCo, the default), `real` (hardware, ticking at `[platform] tick_hz`) and `mock` (no
/// backend, 2 ms ticks); plugins `joints_csv` ([`components::plugins::JointRecorder`]), `mcap`
/// ([`components::plugins::McapRecorder`]) and `video` ([`components::plugins::VideoRecorder`]);
/// with the feature `viewer`, `viewer` and `inspector` (the windows); with `zenoh`, `zenoh`
/// (`components::plugins::ZenohBridge`); with `dataset`, `dataset`
/// (`components::plugins::DatasetRecorder`): plain names, as the features that bring them may
/// be off when these docs are built.
///
/// # Examples
///
/// ```
/// use yarok::components::robots::AnetA30;
/// use yarok::components::worlds::PrinterWorld;
///
/// yarok::platform()
///     .world::<PrinterWorld>()
///     .behaviour(|pl| async move {
///         let printer: AnetA30 = pl.get("/printer")?;
///         let target = printer.move_to([100.0, 50.0, 300.0]);
///         pl.wait(|| printer.is_at(target)).timeout(5.0).await?;
///         Ok(())
///     })
///     .run()?;
/// # Ok::<(), yarok::RuntimeError>(())
/// ```
pub fn platform() -> PlatformBuilder {
    let builder = Platform::builder()
        .backend::<mjc::Sim>(mjc::SimBackend::from_settings)
        .backend::<hw::Real>(hw::HardwareBackend::from_settings)
        .backend::<Mock>(|composition, settings| {
            let declared = mjc::DeclaredWorld::new(composition, settings)?;
            Ok(MockBackend::new(MOCK_TIMESTEP, false).with_world(std::rc::Rc::new(declared)))
        })
        .plugin_factory("joints_csv", components::plugins::JointRecorder::new)
        .plugin_factory("mcap", components::plugins::McapRecorder::new)
        .plugin_factory("video", components::plugins::VideoRecorder::new);
    #[cfg(feature = "viewer")]
    let builder = builder
        .plugin_factory("viewer", components::plugins::Viewer::new)
        .plugin_factory("inspector", components::plugins::Inspector::new);
    #[cfg(feature = "zenoh")]
    let builder = builder.plugin_factory("zenoh", components::plugins::ZenohBridge::new);
    #[cfg(feature = "dataset")]
    let builder = builder.plugin_factory("dataset", components::plugins::DatasetRecorder::new);
    builder
}
