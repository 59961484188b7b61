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
pub(crate) mod sim_state;
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

/// The environments of a plugin that needs MuJoCo ([`Plugin::environments`](yarok_core::runtime::Plugin::environments)).
pub(crate) fn only_sim() -> Vec<&'static str> {
    use yarok_core::component::Environment;
    vec![yarok_mjc::Sim::NAME]
}

/// The MuJoCo backend of a plugin that runs only in `sim` ([`only_sim`]: the platform checked
/// the environment before the plugin started).
pub(crate) fn sim_backend<'a>(
    world: &yarok_core::runtime::World<'a>,
) -> Result<&'a yarok_mjc::SimBackend, yarok_core::BoxError> {
    world.backend().ok_or_else(|| {
        format!(
            "the backend of `{}` is not MuJoCo's",
            world.pl().environment()
        )
        .into()
    })
}
