//! yarok-hw: the real-hardware side of yarok.
//!
//! Its one job is talking to devices: the hardware backend that ticks on wall-clock time, and
//! async drivers generic over their transport (Marlin G-code over serial, the UR controller's
//! URScript and RTDE, the Robotiq gripper socket, cameras).
//!
//! - [`Real`] and [`HardwareBackend`]: the `real` environment, ticking on wall-clock time;
//! - [`marlin`]: Marlin printers (G-code over a serial port or any byte stream);
//! - [`ur`]: the UR controller (RTDE, the secondary interface, the dashboard, the streaming
//!   program that carries joint targets with a watchdog);
//! - [`robotiq`]: the Robotiq gripper's URCap socket;
//! - `camera` (feature `camera`): Video4Linux2 and command-line cameras;
//! - [`SerialPort`], [`connect_within`] and [`reopen`]: the transports and their bounded
//!   connection and reconnection.

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
