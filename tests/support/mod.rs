//! Helpers the workspace's integration tests share; the test doubles (fake controllers, scripted
//! printers, third-party peers) are the `yarok-test` crate's.
// Each test uses part of it.
#![allow(dead_code)]

pub(crate) mod digit_world_recording;
pub(crate) mod example_binary;
pub(crate) mod joints_csv;
pub(crate) mod simulated_ur;
pub(crate) mod yarok_binary;
