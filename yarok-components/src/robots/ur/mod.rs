//! Universal Robots arms: the UR5 (CB3) and the UR5e, their closed-form kinematics, and motions
//! with the meaning of the controller's `movej`, `movel` and `stopj`.

mod arm;
mod component;
mod config;
mod controller;
mod drive;
mod error;
mod exposed;
mod kinematics;
mod measured;
mod mock;
mod model;
mod path;
mod payload;
mod real;
mod sim;
mod streaming;

pub use crate::robots::motions::{
    ARRIVED_M, ARRIVED_RAD, MOVE_J_DEFAULTS, MOVE_L_DEFAULTS, SETTLE_SECONDS,
};
pub use arm::Arm;
pub use config::{ArmConfig, ArmNames};
pub use drive::{ArmDrive, Order, Setpoint};
pub use error::MotionError;
pub use kinematics::{
    DhParameters, IkError, JointLimits, Joints, Kinematics, Solutions, pose_from_vector,
    pose_to_vector,
};
pub use measured::{MeasuredKinematics, isometry_of};
/// A UR arm's motion about to start ([`Arm::move_j`], [`Arm::move_l`]): `.await` it, or
/// [`Motion::start`](crate::robots::Motion::start) it.
pub type Move<'a> = crate::robots::Motion<'a, MotionError>;
pub use path::PathError;
pub use payload::Payload;
pub use streaming::{ServoLimits, UR_JOINT_ACCELERATION, UR_JOINT_SPEED};

pub use component::{Ur5, Ur5Model, Ur5e, Ur5eModel, UrArm, UrModel};
