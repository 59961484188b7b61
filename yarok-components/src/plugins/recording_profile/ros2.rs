//! The ROS 2 profile: CDR-encoded messages of ROS 2's own types, each schema the type's
//! message definition with those it uses (`ros2msg`), as `ros2 bag record` writes them into
//! MCAP: `sensor_msgs/msg/JointState`, `tf2_msgs/msg/TFMessage`,
//! `sensor_msgs/msg/CompressedImage` (PNG), depth as `sensor_msgs/msg/Image` (`32FC1`, metres,
//! as REP 118 has it), `rcl_interfaces/msg/Log` and `rosgraph_msgs/msg/Clock`.

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_mjc::Pose;

use super::{JointValues, MessageKind, RecordingProfile, Schema, nanoseconds};
use crate::plugins::cdr::Cdr;
use crate::probe_images;

/// See the [module](self).
#[derive(Debug)]
pub(super) struct Ros2;

/// What separates a message definition from those it uses.
macro_rules! used {
    ($name:literal, $definition:expr) => {
        concat!(
            "================================================================================\n",
            "MSG: ",
            $name,
            "\n",
            $definition
        )
    };
}

macro_rules! time {
    () => {
        "int32 sec\nuint32 nanosec\n"
    };
}
macro_rules! header {
    () => {
        concat!(
            used!(
                "std_msgs/Header",
                "builtin_interfaces/Time stamp\nstring frame_id\n"
            ),
            used!("builtin_interfaces/Time", time!())
        )
    };
}

const JOINT_STATE: &str = concat!(
    "std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\n",
    "float64[] effort\n",
    header!()
);

const TF_MESSAGE: &str = concat!(
    "geometry_msgs/TransformStamped[] transforms\n",
    used!(
        "geometry_msgs/TransformStamped",
        "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"
    ),
    used!(
        "geometry_msgs/Transform",
        "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"
    ),
    used!("geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"),
    used!(
        "geometry_msgs/Quaternion",
        "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"
    ),
    header!()
);

const COMPRESSED_IMAGE: &str = concat!(
    "std_msgs/Header header\nstring format\nuint8[] data\n",
    header!()
);

const IMAGE: &str = concat!(
    "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\n",
    "uint8 is_bigendian\nuint32 step\nuint8[] data\n",
    header!()
);

const LOG: &str = concat!(
    "byte DEBUG=10\nbyte INFO=20\nbyte WARN=30\nbyte ERROR=40\nbyte FATAL=50\n",
    "builtin_interfaces/Time stamp\nuint8 level\nstring name\nstring msg\nstring file\n",
    "string function\nuint32 line\n",
    used!("builtin_interfaces/Time", time!())
);

const CLOCK: &str = concat!(
    "builtin_interfaces/Time clock\n",
    used!("builtin_interfaces/Time", time!())
);

/// `rcl_interfaces/msg/Log`'s level of information.
const INFO: u8 = 20;

/// A `std_msgs/Header`.
fn header(cdr: &mut Cdr, time: f64, frame: &str) {
    cdr.time(nanoseconds(time)).string(frame);
}

impl RecordingProfile for Ros2 {
    fn mcap_profile(&self) -> &'static str {
        "ros2"
    }

    fn message_encoding(&self) -> &'static str {
        "cdr"
    }

    fn schema(&self, kind: MessageKind) -> Option<Schema> {
        let (name, data) = match kind {
            MessageKind::JointState => ("sensor_msgs/msg/JointState", JOINT_STATE),
            MessageKind::Transforms => ("tf2_msgs/msg/TFMessage", TF_MESSAGE),
            MessageKind::Image => ("sensor_msgs/msg/CompressedImage", COMPRESSED_IMAGE),
            MessageKind::Depth => ("sensor_msgs/msg/Image", IMAGE),
            MessageKind::Log => ("rcl_interfaces/msg/Log", LOG),
            MessageKind::Clock => ("rosgraph_msgs/msg/Clock", CLOCK),
            MessageKind::State => ("std_msgs/msg/String", "string data\n"),
        };
        Some(Schema {
            name,
            encoding: "ros2msg",
            data,
        })
    }

    fn joint_state(&self, time: f64, joints: &JointValues<'_>) -> Vec<u8> {
        let mut cdr = Cdr::new();
        header(&mut cdr, time, "");
        cdr.strings(joints.names.iter().map(String::as_str))
            .f64s(joints.positions)
            .f64s(joints.velocities)
            .f64s(&[]);
        cdr.finish()
    }

    fn transforms(&self, time: f64, frames: &[String], poses: &[Pose]) -> Vec<u8> {
        let mut cdr = Cdr::new();
        cdr.sequence(
            frames.iter().zip(poses),
            |cdr, (name, Pose { pos, quat })| {
                header(cdr, time, "world");
                cdr.string(name);
                for value in pos {
                    cdr.f64(*value);
                }
                // MuJoCo's quaternions are w first; ROS's w last.
                for value in [quat[1], quat[2], quat[3], quat[0]] {
                    cdr.f64(value);
                }
            },
        );
        cdr.finish()
    }

    fn image(&self, time: f64, frame: &str, image: &ProbeImage) -> Result<Vec<u8>, BoxError> {
        let mut cdr = Cdr::new();
        header(&mut cdr, time, frame);
        match image {
            ProbeImage::Rgb { .. } => {
                cdr.string("png").bytes(&probe_images::png(image)?);
            }
            ProbeImage::Depth {
                width,
                height,
                metres,
                ..
            } => {
                let data: Vec<u8> = metres.iter().flat_map(|m| m.to_le_bytes()).collect();
                cdr.u32(*height)
                    .u32(*width)
                    .string("32FC1")
                    .u8(0)
                    .u32(width * 4)
                    .bytes(&data);
            }
            other => return Err(format!("no ROS 2 message for an image like {other:?}").into()),
        }
        Ok(cdr.finish())
    }

    /// Depth is `32FC1` in metres, whatever the probe counts in.
    fn depth_unit_m(&self, _probe_unit: f32) -> f32 {
        1.0
    }

    fn log(&self, time: f64, text: &str) -> Vec<u8> {
        let mut cdr = Cdr::new();
        cdr.time(nanoseconds(time))
            .u8(INFO)
            .string("behaviour")
            .string(text)
            .string("")
            .string("")
            .u32(0);
        cdr.finish()
    }

    /// The state as JSON text in a `std_msgs/msg/String`.
    fn state(&self, _time: f64, value: &serde_json::Value) -> Vec<u8> {
        let mut cdr = Cdr::new();
        cdr.string(&value.to_string());
        cdr.finish()
    }

    fn clock(&self, time: f64) -> Option<Vec<u8>> {
        Some(Cdr::new().time(nanoseconds(time)).finish())
    }
}
