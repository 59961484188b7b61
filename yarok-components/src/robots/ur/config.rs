//! [`ArmConfig`]: how an [`Arm`](super::Arm) drives a model — kinematics, names and start.

use super::kinematics::{DhParameters, Joints, Kinematics};

/// The joint and actuator names of a UR model, base to wrist 3, and its flange site.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArmNames {
    /// The hinge joints.
    pub joints: [&'static str; 6],
    /// The position servos driving them.
    pub actuators: [&'static str; 6],
    /// The site at the flange (the real arm's `tool0`, where tools attach).
    pub flange: &'static str,
}

impl ArmNames {
    /// The names in yarok's own [`Ur5`](super::Ur5) and [`Ur5e`](super::Ur5e) templates.
    pub const YAROK: Self = Self {
        joints: JOINTS,
        actuators: JOINTS,
        flange: "flange",
    };

    /// The names in MuJoCo Menagerie's `universal_robots_ur5e/ur5e.xml`.
    pub const MENAGERIE: Self = Self {
        joints: [
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint",
        ],
        actuators: JOINTS,
        flange: "attachment_site",
    };
}

const JOINTS: [&str; 6] = [
    "shoulder_pan",
    "shoulder_lift",
    "elbow",
    "wrist_1",
    "wrist_2",
    "wrist_3",
];

/// How an [`Arm`](super::Arm) drives a model: its kinematics, names and where it starts. The
/// servos' gains come from the model's actuators.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmConfig {
    /// Kinematics with the joint limits and TCP the motions use.
    pub kinematics: Kinematics,
    /// Joint and actuator names in the model.
    pub names: ArmNames,
    /// Joint angles at the start of a run; `None` keeps the model's.
    pub start: Option<Joints>,
}

impl ArmConfig {
    /// An arm of `dh`, with yarok's names, starting where the model does.
    pub fn new(dh: DhParameters) -> Self {
        Self {
            kinematics: Kinematics::new(dh),
            names: ArmNames::YAROK,
            start: None,
        }
    }
}
