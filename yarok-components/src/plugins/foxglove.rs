//! The messages a recording holds, as JSON in the shapes Foxglove's well-known schemas give
//! them (`foxglove.FrameTransforms`, `foxglove.CompressedImage`, `foxglove.Log`), and joint
//! states shaped as ROS's `sensor_msgs/JointState`; each with the JSON Schema that describes
//! it.

use base64::Engine;
use serde_json::{Value, json};
use yarok_mjc::Pose;

/// A message kind: its schema's name and JSON Schema.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Schema {
    pub(crate) name: &'static str,
    pub(crate) json_schema: &'static str,
}

pub(crate) const JOINT_STATE: Schema = Schema {
    name: "yarok.JointState",
    json_schema: include_str!("schemas/joint_state.json"),
};

pub(crate) const FRAME_TRANSFORMS: Schema = Schema {
    name: "foxglove.FrameTransforms",
    json_schema: include_str!("schemas/frame_transforms.json"),
};

pub(crate) const COMPRESSED_IMAGE: Schema = Schema {
    name: "foxglove.CompressedImage",
    json_schema: include_str!("schemas/compressed_image.json"),
};

pub(crate) const LOG: Schema = Schema {
    name: "foxglove.Log",
    json_schema: include_str!("schemas/log.json"),
};

/// Platform time in nanoseconds, as MCAP's log times count it.
pub(crate) fn nanoseconds(seconds: f64) -> u64 {
    (seconds.max(0.0) * 1e9).round() as u64
}

fn timestamp(seconds: f64) -> Value {
    let nanos = nanoseconds(seconds);
    json!({ "sec": nanos / 1_000_000_000, "nsec": nanos % 1_000_000_000 })
}

/// Joint coordinates' names, positions and velocities at `time`.
pub(crate) fn joint_state(
    time: f64,
    names: &[String],
    positions: &[f64],
    velocities: &[f64],
) -> Value {
    json!({
        "timestamp": timestamp(time),
        "name": names,
        "position": positions,
        "velocity": velocities,
    })
}

/// Bodies' poses in the world frame at `time`.
pub(crate) fn frame_transforms<'a>(
    time: f64,
    bodies: impl Iterator<Item = (&'a str, Pose)>,
) -> Value {
    let stamp = timestamp(time);
    let transforms: Vec<Value> = bodies
        .map(|(name, Pose { pos, quat })| {
            json!({
                "timestamp": stamp,
                "parent_frame_id": "world",
                "child_frame_id": name,
                "translation": { "x": pos[0], "y": pos[1], "z": pos[2] },
                "rotation": { "x": quat[1], "y": quat[2], "z": quat[3], "w": quat[0] },
            })
        })
        .collect();
    json!({ "transforms": transforms })
}

/// A PNG image of frame `frame` at `time`.
pub(crate) fn png_image(time: f64, frame: &str, png: &[u8]) -> Value {
    json!({
        "timestamp": timestamp(time),
        "frame_id": frame,
        "data": base64::engine::general_purpose::STANDARD.encode(png),
        "format": "png",
    })
}

/// A behaviour's log line at `time`.
pub(crate) fn log(time: f64, text: &str) -> Value {
    json!({
        "timestamp": timestamp(time),
        "level": 2,
        "message": text,
        "name": "behaviour",
        "file": "",
        "line": 0,
    })
}
