//! yarok-hw: the real-hardware side of yarok.
//!
//! Its one job is talking to devices: the hardware backend that ticks on wall-clock time, and
//! async drivers generic over their transport (Marlin G-code over serial, the UR controller's
//! URScript and RTDE, the Robotiq gripper socket, cameras).
//!
//! This crate is being built up issue by issue; today it holds the hardware backend, the
//! Marlin driver, serial ports, cameras (feature `camera`) and the UR controller's RTDE client.

mod backend;
#[cfg(feature = "camera")]
pub mod camera;
pub mod marlin;
mod reading;
mod reopen;
pub mod robotiq;
mod serial;
mod tcp;
pub mod ur;

pub use backend::{DEFAULT_TICK_HZ, HardwareBackend, InvalidTickRate, Real};
pub use reopen::{FIRST_RETRY, reopen};
pub use serial::{SerialError, SerialPort};
pub use tcp::{ConnectError, connect_within};
