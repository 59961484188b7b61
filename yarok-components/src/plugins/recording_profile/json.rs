//! The JSON profile: messages in the shapes of Foxglove's well-known schemas, joint states
//! shaped as ROS's `sensor_msgs/JointState`, each kind with its JSON Schema; images as PNG.

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_mjc::Pose;

use super::{JointValues, MessageKind, RecordingProfile, Schema};
use crate::plugins::foxglove;
use crate::probe_images;

/// See the [module](self).
#[derive(Debug)]
pub(crate) struct Json;

fn json_schema(schema: foxglove::Schema) -> Schema {
    Schema {
        name: schema.name,
        encoding: "jsonschema",
        data: schema.json_schema,
    }
}

fn bytes(message: &serde_json::Value) -> Vec<u8> {
    serde_json::to_vec(message).expect("a JSON value serialises")
}

impl RecordingProfile for Json {
    fn mcap_profile(&self) -> &'static str {
        ""
    }

    fn message_encoding(&self) -> &'static str {
        "json"
    }

    fn schema(&self, kind: MessageKind) -> Option<Schema> {
        let schema = match kind {
            MessageKind::JointState => foxglove::JOINT_STATE,
            MessageKind::Transforms => foxglove::FRAME_TRANSFORMS,
            // Depth too: a 16-bit PNG.
            MessageKind::Image | MessageKind::Depth => foxglove::COMPRESSED_IMAGE,
            MessageKind::Log => foxglove::LOG,
            MessageKind::Clock => return None,
        };
        Some(json_schema(schema))
    }

    fn joint_state(&self, time: f64, joints: &JointValues<'_>) -> Vec<u8> {
        bytes(&foxglove::joint_state(
            time,
            joints.names,
            &joints.positions,
            &joints.velocities,
        ))
    }

    fn transforms(&self, time: f64, bodies: &[(&str, Pose)]) -> Vec<u8> {
        bytes(&foxglove::frame_transforms(time, bodies.iter().copied()))
    }

    fn image(&self, time: f64, frame: &str, image: &ProbeImage) -> Result<Vec<u8>, BoxError> {
        let png = probe_images::png(image)?;
        Ok(bytes(&foxglove::png_image(time, frame, &png)))
    }

    fn log(&self, time: f64, text: &str) -> Vec<u8> {
        bytes(&foxglove::log(time, text))
    }

    fn clock(&self, _time: f64) -> Option<Vec<u8>> {
        None
    }
}
