//! Any serial arm in MJCF, unmodified — a Franka Panda, a KUKA iiwa, an xArm, a Kinova — driven
//! with the UR arms' motions: [`SerialArm`] given the arm's joints, actuators and TCP
//! ([`SerialNames`], with mappings for robosuite's files), its kinematics MuJoCo's own
//! ([`SerialKinematics`]). The UR arms keep their exact closed form
//! ([`ur::Kinematics`](super::ur::Kinematics)).

mod actuated_joints;
mod arm;
mod controller;
mod dynamics;
mod error;
mod kinematics;
mod names;

pub use arm::{DEFAULT_STIFFNESS, SerialArm, SerialMove};
pub use error::{SerialMotionError, StuckCause};
pub use kinematics::{SOLVED, SerialIkError, SerialKinematics, TcpFrame};
pub use names::SerialNames;
