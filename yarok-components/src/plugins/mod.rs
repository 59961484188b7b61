//! Plugins: code that runs beside the behaviours and sees the world.

mod joint_recorder;

pub use joint_recorder::{JointRecorder, JointRecorderSettings};
