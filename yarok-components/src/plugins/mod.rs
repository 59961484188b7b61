//! Plugins: code that runs beside the behaviours and sees the world.

mod bounded_wait;
mod cdr;
#[cfg(feature = "dataset")]
mod dataset_recorder;
mod encoder;
#[cfg(feature = "viewer")]
mod inspector;
mod joint_recorder;
mod mcap_recorder;
mod recording_profile;
mod sim_state;
mod status_line;
mod video_recorder;
#[cfg(feature = "viewer")]
mod viewer;
#[cfg(feature = "zenoh")]
mod zenoh_bridge;

#[cfg(feature = "dataset")]
pub use dataset_recorder::{DatasetRecorder, DatasetRecorderSettings};
#[cfg(feature = "viewer")]
pub use inspector::{Inspector, InspectorSettings};
pub use joint_recorder::{JointRecorder, JointRecorderSettings};
pub use mcap_recorder::{McapRecorder, McapRecorderSettings};
pub use status_line::StatusLine;
pub use video_recorder::{VideoRecorder, VideoRecorderSettings};
#[cfg(feature = "viewer")]
pub use viewer::{Viewer, ViewerSettings};
#[cfg(feature = "zenoh")]
pub use zenoh_bridge::{ZenohBridge, ZenohBridgeSettings};

/// The render preset of a recorder's cameras: MuJoCo's defaults when `quality` is asked for,
/// else the fast one (software GL renders it several times faster).
fn preset(quality: bool) -> yarok_mjc::RenderPreset {
    if quality {
        yarok_mjc::RenderPreset::Quality
    } else {
        yarok_mjc::RenderPreset::Fast
    }
}
