//! [`ArmConfig`]: how an [`Arm`](super::Arm) drives a model — kinematics, names, start and servo
//! gains.

use super::kinematics::{DhParameters, Joints, Kinematics};

/// The joint and actuator names of a UR model, base to wrist 3.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArmNames {
    /// The hinge joints.
    pub joints: [&'static str; 6],
    /// The position servos driving them.
    pub actuators: [&'static str; 6],
}

impl ArmNames {
    /// The names in yarok's own [`Ur5`](super::Ur5) and [`Ur5e`](super::Ur5e) templates.
    pub const YAROK: Self = Self {
        joints: JOINTS,
        actuators: JOINTS,
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

/// How an [`Arm`](super::Arm) drives a model: its kinematics, names, where it starts, and the gains of its
/// position servos, from which the arm feeds the motion's speed and acceleration forward (a
/// servo that damps the joint's velocity lags a moving target by `kv / kp` times its speed;
/// accelerating the joint's inertia takes force too), so that it tracks without lag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmConfig {
    /// Kinematics with the joint limits and TCP the motions use.
    pub kinematics: Kinematics,
    /// Joint and actuator names in the model.
    pub names: ArmNames,
    /// Joint angles at the start of a run; `None` keeps the model's.
    pub start: Option<Joints>,
    /// `(kp, kv)` of each servo (force per radian of error, per rad/s of joint speed); a
    /// zero `kp` feeds nothing forward.
    pub gains: [(f64, f64); 6],
}

impl ArmConfig {
    /// An arm of `dh`, with yarok's names, starting where the model does, without feed-forward.
    pub fn new(dh: DhParameters) -> Self {
        Self {
            kinematics: Kinematics::new(dh),
            names: ArmNames::YAROK,
            start: None,
            gains: [(0.0, 0.0); 6],
        }
    }
}
