//! Grippers: [`ParallelGripper`], any two-finger gripper, and the Robotiq 2F-85 built on it.

pub mod parallel;
mod robotiq_2f85;

pub use parallel::{Grip, Gripped, GripperNames, ParallelGripper, REACHED_COUNTS};
pub use robotiq_2f85::Robotiq2f85;
