//! [`SerialNames`]: which joints, actuators and TCP frame of a model make a serial arm.

/// The names of a serial arm in its model: its joints base to tip, the actuator driving each
/// (a `<motor>` or a position servo), and the TCP frame (a site, or else a body). Mappings for
/// the common files are constants.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SerialNames {
    /// The hinge or slide joints, base to tip.
    pub joints: &'static [&'static str],
    /// The actuator of each joint, in the same order; none (`&[]`) to use the actuator that
    /// drives each joint, named or not (files whose actuators have no names).
    pub actuators: &'static [&'static str],
    /// The TCP: a site's name, or a body's (for files with no site at the hand).
    pub tcp: &'static str,
}

const ROBOSUITE_MOTORS: [&str; 7] = [
    "torq_j1", "torq_j2", "torq_j3", "torq_j4", "torq_j5", "torq_j6", "torq_j7",
];

impl SerialNames {
    /// robosuite's Franka Panda (`robots/panda/robot.xml`): seven joints on torque motors, the
    /// TCP at the body `right_hand`.
    pub const ROBOSUITE_PANDA: Self = Self {
        joints: &[
            "joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint7",
        ],
        actuators: &ROBOSUITE_MOTORS,
        tcp: "right_hand",
    };

    /// robosuite's KUKA LBR iiwa (`robots/iiwa/robot.xml`).
    pub const ROBOSUITE_IIWA: Self = Self {
        joints: &[
            "joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6", "joint_7",
        ],
        actuators: &ROBOSUITE_MOTORS,
        tcp: "right_hand",
    };

    /// robosuite's Kinova Gen3 (`robots/kinova3/robot.xml`).
    pub const ROBOSUITE_KINOVA3: Self = Self {
        joints: &[
            "Actuator1",
            "Actuator2",
            "Actuator3",
            "Actuator4",
            "Actuator5",
            "Actuator6",
            "Actuator7",
        ],
        actuators: &ROBOSUITE_MOTORS,
        tcp: "right_hand",
    };

    /// robosuite's Rethink Sawyer (`robots/sawyer/robot.xml`); its head pan joint is not part
    /// of the arm.
    pub const ROBOSUITE_SAWYER: Self = Self {
        joints: &[
            "right_j0", "right_j1", "right_j2", "right_j3", "right_j4", "right_j5", "right_j6",
        ],
        actuators: &[
            "torq_right_j0",
            "torq_right_j1",
            "torq_right_j2",
            "torq_right_j3",
            "torq_right_j4",
            "torq_right_j5",
            "torq_right_j6",
        ],
        tcp: "right_hand",
    };

    /// robosuite's Kinova Jaco (`robots/jaco/robot.xml`).
    pub const ROBOSUITE_JACO: Self = Self {
        joints: &[
            "j2s7s300_joint_1",
            "j2s7s300_joint_2",
            "j2s7s300_joint_3",
            "j2s7s300_joint_4",
            "j2s7s300_joint_5",
            "j2s7s300_joint_6",
            "j2s7s300_joint_7",
        ],
        actuators: &ROBOSUITE_MOTORS,
        tcp: "right_hand",
    };

    /// robosuite's UR5e (`robots/ur5e/robot.xml`), as a serial arm (the UR arms' own
    /// [`Arm`](crate::robots::ur::Arm) has its exact kinematics).
    pub const ROBOSUITE_UR5E: Self = Self {
        joints: &[
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint",
        ],
        actuators: ROBOSUITE_MOTORS.split_at(6).0,
        tcp: "right_hand",
    };

    /// robosuite's UFactory xArm 7 (`robots/xarm7/robot.xml`).
    pub const ROBOSUITE_XARM7: Self = Self {
        joints: &[
            "joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint7",
        ],
        actuators: &ROBOSUITE_MOTORS,
        tcp: "right_hand",
    };

    /// The right arm of robosuite's Rethink Baxter (`robots/baxter/robot.xml`).
    pub const ROBOSUITE_BAXTER_RIGHT: Self = Self {
        joints: &[
            "right_s0", "right_s1", "right_e0", "right_e1", "right_w0", "right_w1", "right_w2",
        ],
        actuators: &[
            "torq_right_j0",
            "torq_right_j1",
            "torq_right_j2",
            "torq_right_j3",
            "torq_right_j4",
            "torq_right_j5",
            "torq_right_j6",
        ],
        tcp: "right_hand",
    };

    /// The left arm of robosuite's Rethink Baxter.
    pub const ROBOSUITE_BAXTER_LEFT: Self = Self {
        joints: &[
            "left_s0", "left_s1", "left_e0", "left_e1", "left_w0", "left_w1", "left_w2",
        ],
        actuators: &[
            "torq_left_j0",
            "torq_left_j1",
            "torq_left_j2",
            "torq_left_j3",
            "torq_left_j4",
            "torq_left_j5",
            "torq_left_j6",
        ],
        tcp: "left_hand",
    };

    /// The right arm of robosuite's PAL Tiago (`robots/tiago/robot.xml`); its torso and head
    /// are not part of it.
    pub const ROBOSUITE_TIAGO_RIGHT: Self = Self {
        joints: &[
            "arm_right_1_joint",
            "arm_right_2_joint",
            "arm_right_3_joint",
            "arm_right_4_joint",
            "arm_right_5_joint",
            "arm_right_6_joint",
        ],
        actuators: &[
            "torq_right_j1",
            "torq_right_j2",
            "torq_right_j3",
            "torq_right_j4",
            "torq_right_j5",
            "torq_right_j6",
        ],
        tcp: "right_hand",
    };

    /// The left arm of robosuite's PAL Tiago.
    pub const ROBOSUITE_TIAGO_LEFT: Self = Self {
        joints: &[
            "arm_left_1_joint",
            "arm_left_2_joint",
            "arm_left_3_joint",
            "arm_left_4_joint",
            "arm_left_5_joint",
            "arm_left_6_joint",
        ],
        actuators: &[
            "torq_left_j1",
            "torq_left_j2",
            "torq_left_j3",
            "torq_left_j4",
            "torq_left_j5",
            "torq_left_j6",
        ],
        tcp: "left_hand",
    };

    /// The arm of robosuite's Boston Dynamics Spot (`robots/spot_arm/robot.xml`), on the
    /// motors its file names after the joints.
    pub const ROBOSUITE_SPOT_ARM: Self = Self {
        joints: &[
            "arm_sh0", "arm_sh1", "arm_el0", "arm_el1", "arm_wr0", "arm_wr1",
        ],
        actuators: &[
            "arm_sh0", "arm_sh1", "arm_el0", "arm_el1", "arm_wr0", "arm_wr1",
        ],
        tcp: "right_hand",
    };
}
