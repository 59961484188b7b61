//! Grippers: [`ParallelGripper`], any two-finger gripper, and the Robotiq 2F-85 built on it.

pub mod parallel;
mod robotiq_2f85;

pub use parallel::{
    FingerServo, Grip, Gripped, GripperNames, GripperParts, ParallelGripper, REACHED_COUNTS, Stroke,
};
pub use robotiq_2f85::Robotiq2f85;
