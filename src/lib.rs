//! yarok: compose robots and robotic environments from reusable MJCF components, simulate them in
//! MuJoCo, and run the same async behaviour code on real hardware.
//!
//! This facade re-exports the workspace crates:
//!
//! - [`core`] (`yarok-core`): templates, composition, config and the async runtime;
//! - [`mjc`] (`yarok-mjc`): MuJoCo bindings, safe model/data, headless rendering;
//! - [`hw`] (`yarok-hw`): the hardware backend and device drivers;
//! - [`components`] (`yarok-components`): the bundled components.
//!
//! # Cargo features
//!
//! - `render` (default): offscreen camera rendering through EGL (see [`mjc::Renderer`]).
//!
//! # The project's README
//!
#![doc = include_str!("../README.md")]

pub use yarok_components as components;
pub use yarok_core as core;
pub use yarok_hw as hw;
pub use yarok_mjc as mjc;
