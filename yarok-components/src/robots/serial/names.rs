//! [`SerialNames`]: which joints, actuators and TCP frame of a model make a serial arm.

/// The names of a serial arm in its model: its joints base to tip, the actuator driving each
/// (a `<motor>` or a position servo), and the TCP frame (a site, or else a body). Mappings for
/// the common files are constants.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SerialNames {
    /// The hinge or slide joints, base to tip.
    pub joints: &'static [&'static str],
    /// The actuator of each joint, in the same order.
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
}
