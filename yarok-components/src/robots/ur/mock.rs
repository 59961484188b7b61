//! [`FollowingJoints`]: an arm in `mock`, whose joints follow its motions exactly.

use super::drive::{ArmDrive, Setpoint};
use super::kinematics::Joints;

/// Joints that are where they are commanded, at the speed commanded.
pub(super) struct FollowingJoints;

impl ArmDrive for FollowingJoints {
    fn q(&self, commanded: &Setpoint) -> Joints {
        commanded.q
    }

    fn qd(&self, commanded: &Setpoint) -> Joints {
        commanded.speed
    }
}
