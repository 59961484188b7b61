//! The Foxglove profile: JSON messages in the shapes of Foxglove's well-known schemas
//! (`foxglove.JointStates`, `foxglove.FrameTransforms`, `foxglove.CompressedImage`,
//! `foxglove.RawImage`, `foxglove.Log`), each channel with a self-contained JSON Schema (no
//! `$ref`, which the open-source Foxglove Studio and Lichtblick parsers do not resolve); colour
//! images as PNG, depth as raw `16UC1` counts of the probe's unit, which Foxglove's Image panel
//! colours by its depth settings (a browser decodes a 16-bit PNG to 8 bits).

use base64::Engine;
use serde::Serialize;
use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_mjc::Pose;

use super::{JointValues, MessageKind, RecordingProfile, Schema, nanoseconds};
use crate::probe_images;

/// See the [module](self).
#[derive(Debug)]
pub(crate) struct Foxglove;

fn schema(name: &'static str, data: &'static str) -> Schema {
    Schema {
        name,
        encoding: "jsonschema",
        data,
    }
}

#[derive(Serialize)]
struct Time {
    sec: u64,
    nsec: u64,
}

impl Time {
    fn at(seconds: f64) -> Self {
        let nanos = nanoseconds(seconds);
        Self {
            sec: nanos / 1_000_000_000,
            nsec: nanos % 1_000_000_000,
        }
    }
}

#[derive(Serialize)]
struct JointStates<'a> {
    timestamp: Time,
    joints: Vec<Joint<'a>>,
}

#[derive(Serialize)]
struct Joint<'a> {
    name: &'a str,
    position: f64,
    velocity: f64,
}

#[derive(Serialize)]
struct FrameTransforms<'a> {
    transforms: Vec<FrameTransform<'a>>,
}

#[derive(Serialize)]
struct FrameTransform<'a> {
    timestamp: Time,
    parent_frame_id: &'static str,
    child_frame_id: &'a str,
    translation: Vector3,
    rotation: Quaternion,
}

#[derive(Serialize)]
struct Vector3 {
    x: f64,
    y: f64,
    z: f64,
}

#[derive(Serialize)]
struct Quaternion {
    x: f64,
    y: f64,
    z: f64,
    w: f64,
}

#[derive(Serialize)]
struct CompressedImage<'a> {
    timestamp: Time,
    frame_id: &'a str,
    data: String,
    format: &'static str,
}

#[derive(Serialize)]
struct RawImage<'a> {
    timestamp: Time,
    frame_id: &'a str,
    width: u32,
    height: u32,
    encoding: &'static str,
    step: u32,
    data: String,
}

#[derive(Serialize)]
struct Log<'a> {
    timestamp: Time,
    level: u8,
    message: &'a str,
    name: &'static str,
    file: &'static str,
    line: u32,
}

/// `foxglove.Log`'s level of information.
const INFO: u8 = 2;

fn bytes(message: &impl Serialize) -> Vec<u8> {
    serde_json::to_vec(message).expect("numbers and strings serialise")
}

impl RecordingProfile for Foxglove {
    fn mcap_profile(&self) -> &'static str {
        ""
    }

    fn message_encoding(&self) -> &'static str {
        "json"
    }

    fn schema(&self, kind: MessageKind) -> Option<Schema> {
        Some(match kind {
            MessageKind::JointState => schema(
                "foxglove.JointStates",
                include_str!("foxglove_schemas/joint_states.json"),
            ),
            MessageKind::Transforms => schema(
                "foxglove.FrameTransforms",
                include_str!("foxglove_schemas/frame_transforms.json"),
            ),
            MessageKind::Image => schema(
                "foxglove.CompressedImage",
                include_str!("foxglove_schemas/compressed_image.json"),
            ),
            MessageKind::Depth => schema(
                "foxglove.RawImage",
                include_str!("foxglove_schemas/raw_image.json"),
            ),
            MessageKind::Log => schema("foxglove.Log", include_str!("foxglove_schemas/log.json")),
            MessageKind::State => {
                schema("yarok.State", include_str!("foxglove_schemas/state.json"))
            }
            MessageKind::Clock => return None,
        })
    }

    fn joint_state(&self, time: f64, joints: &JointValues<'_>) -> Vec<u8> {
        let joints = joints
            .names
            .iter()
            .zip(joints.positions)
            .zip(joints.velocities)
            .map(|((name, &position), &velocity)| Joint {
                name,
                position,
                velocity,
            })
            .collect();
        bytes(&JointStates {
            timestamp: Time::at(time),
            joints,
        })
    }

    fn transforms(&self, time: f64, frames: &[String], poses: &[Pose]) -> Vec<u8> {
        let transforms = frames
            .iter()
            .zip(poses)
            .map(|(name, &Pose { pos, quat })| FrameTransform {
                timestamp: Time::at(time),
                parent_frame_id: "world",
                child_frame_id: name,
                translation: Vector3 {
                    x: pos[0],
                    y: pos[1],
                    z: pos[2],
                },
                rotation: Quaternion {
                    x: quat[1],
                    y: quat[2],
                    z: quat[3],
                    w: quat[0],
                },
            })
            .collect();
        bytes(&FrameTransforms { transforms })
    }

    fn image(&self, time: f64, frame: &str, image: &ProbeImage) -> Result<Vec<u8>, BoxError> {
        let base64 = |data: &[u8]| base64::engine::general_purpose::STANDARD.encode(data);
        Ok(match image {
            ProbeImage::Depth {
                width,
                height,
                metres,
                unit,
            } => {
                let counts: Vec<u8> = metres
                    .iter()
                    .flat_map(|m| probe_images::counts(*m, *unit).to_le_bytes())
                    .collect();
                bytes(&RawImage {
                    timestamp: Time::at(time),
                    frame_id: frame,
                    width: *width,
                    height: *height,
                    encoding: "16UC1",
                    step: width * 2,
                    data: base64(&counts),
                })
            }
            colour => bytes(&CompressedImage {
                timestamp: Time::at(time),
                frame_id: frame,
                data: base64(&probe_images::png(colour)?),
                format: "png",
            }),
        })
    }

    fn log(&self, time: f64, text: &str) -> Vec<u8> {
        bytes(&Log {
            timestamp: Time::at(time),
            level: INFO,
            message: text,
            name: "behaviour",
            file: "",
            line: 0,
        })
    }

    /// The state's fields with its `timestamp`; a state that is not an object is its `value`.
    fn state(&self, time: f64, value: &serde_json::Value) -> Vec<u8> {
        let mut message = match value {
            serde_json::Value::Object(fields) => fields.clone(),
            other => serde_json::Map::from_iter([("value".to_owned(), other.clone())]),
        };
        let timestamp = serde_json::to_value(Time::at(time)).unwrap_or_default();
        message.insert("timestamp".to_owned(), timestamp);
        bytes(&message)
    }

    fn clock(&self, _time: f64) -> Option<Vec<u8>> {
        None
    }
}
