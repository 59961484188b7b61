//! Universal Robots arms: the UR5 (CB3) and the UR5e, their closed-form kinematics and motions
//! with the meaning of the controller's `movej` and `movel`.

mod kinematics;

pub use kinematics::{
    DhParameters, IkError, JointLimits, Joints, Kinematics, Solutions, pose_from_vector,
    pose_to_vector,
};
