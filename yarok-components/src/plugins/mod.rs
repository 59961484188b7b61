//! Plugins: code that runs beside the behaviours and sees the world.

mod foxglove;
mod joint_recorder;
mod mcap_recorder;
mod status_line;
mod video_recorder;

pub use joint_recorder::{JointRecorder, JointRecorderSettings};
pub use mcap_recorder::{McapRecorder, McapRecorderSettings};
pub use status_line::StatusLine;
pub use video_recorder::{VideoRecorder, VideoRecorderSettings};

/// The render preset of a recorder's cameras: MuJoCo's defaults when `quality` is asked for,
/// else the fast one (software GL renders it several times faster).
fn preset(quality: bool) -> yarok_mjc::RenderPreset {
    if quality {
        yarok_mjc::RenderPreset::Quality
    } else {
        yarok_mjc::RenderPreset::Fast
    }
}
