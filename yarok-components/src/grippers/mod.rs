//! Grippers: the Robotiq 2F-85.

mod robotiq_2f85;

pub use robotiq_2f85::{Grip, Gripped, GripperNames, REACHED_COUNTS, Robotiq2f85};
