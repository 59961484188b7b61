//! [`RecordingProfile`]: how a recording encodes its messages — the MCAP profile it declares,
//! each kind of message's schema, and each message's bytes. One implementation a file:
//! [`foxglove`] (JSON in Foxglove's well-known shapes, the default) and [`ros2`] (CDR with
//! ROS 2 message definitions, for `ros2 bag`).

mod foxglove;
mod ros2;

pub(crate) use foxglove::Foxglove;

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_mjc::Pose;

/// The kinds of message a recording holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MessageKind {
    JointState,
    Transforms,
    /// A colour image, compressed.
    Image,
    /// A depth image.
    Depth,
    Log,
    /// The platform's clock.
    Clock,
    /// A component's named state, as JSON.
    State,
}

/// A schema as an MCAP file states it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Schema {
    pub(crate) name: &'static str,
    pub(crate) encoding: &'static str,
    pub(crate) data: &'static str,
}

/// Joints' names, positions and velocities, one of each a joint.
#[derive(Debug)]
pub(crate) struct JointValues<'a> {
    pub(crate) names: &'a [String],
    pub(crate) positions: &'a [f64],
    pub(crate) velocities: &'a [f64],
}

/// How a recording encodes its messages. Times are platform time, seconds.
pub(crate) trait RecordingProfile: Send + Sync {
    /// The profile the MCAP header declares (`""` for none).
    fn mcap_profile(&self) -> &'static str;

    /// The encoding of every message (`json`, `cdr`).
    fn message_encoding(&self) -> &'static str;

    /// The schema of `kind`, or `None` if this profile does not record it.
    fn schema(&self, kind: MessageKind) -> Option<Schema>;

    fn joint_state(&self, time: f64, joints: &JointValues<'_>) -> Vec<u8>;

    /// The poses of frames `frames` in the world frame, one for one.
    fn transforms(&self, time: f64, frames: &[String], poses: &[Pose]) -> Vec<u8>;

    /// A probe's or camera's image in frame `frame`: a colour image as [`MessageKind::Image`],
    /// a depth image as [`MessageKind::Depth`].
    ///
    /// # Errors
    ///
    /// If the image cannot be encoded.
    fn image(&self, time: f64, frame: &str, image: &ProbeImage) -> Result<Vec<u8>, BoxError>;

    /// The unit (metres) of the numbers this profile writes for a depth image whose probe
    /// counts in `probe_unit` metres: what a depth channel's metadata states.
    fn depth_unit_m(&self, probe_unit: f32) -> f32 {
        probe_unit
    }

    /// A behaviour's log line.
    fn log(&self, time: f64, text: &str) -> Vec<u8>;

    /// A component's named state ([`yarok_core::component::NamedState`]).
    fn state(&self, time: f64, value: &serde_json::Value) -> Vec<u8>;

    /// The platform's clock, if this profile records it (then [`MessageKind::Clock`] has a
    /// schema).
    fn clock(&self, time: f64) -> Option<Vec<u8>>;
}

/// Platform time in nanoseconds, as MCAP's log times count it.
pub(crate) fn nanoseconds(seconds: f64) -> u64 {
    (seconds.max(0.0) * 1e9).round() as u64
}

/// The profile named `name` (`foxglove` or `ros2`).
///
/// # Errors
///
/// If there is no profile of that name, naming the ones there are.
pub(crate) fn named(name: &str) -> Result<Box<dyn RecordingProfile>, String> {
    match name {
        "foxglove" => Ok(Box::new(Foxglove)),
        "ros2" => Ok(Box::new(ros2::Ros2)),
        other => Err(format!(
            "no recording profile {other:?}: there are \"foxglove\" and \"ros2\""
        )),
    }
}
