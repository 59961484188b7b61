//! [`MotionError`]: why a motion did not arrive.

use yarok_core::time::WaitError;

use crate::robots::motions::MotionEnding;

use super::kinematics::{IkError, Joints};
use super::path::PathError;

/// Why a motion did not arrive.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MotionError {
    /// The target or a point on the way cannot be reached; nothing moved.
    #[error("{0}")]
    Path(#[from] PathError),
    /// A target joint is NaN, infinite or outside its limits; nothing moved.
    #[error("target joints {target:?} are not finite or outside the joint limits")]
    InvalidTarget {
        /// The joints asked for.
        target: Joints,
    },
    /// A speed or acceleration is not a positive number.
    #[error("speed {speed} and acceleration {acceleration} must be positive numbers")]
    InvalidLimits {
        /// The speed given.
        speed: f64,
        /// The acceleration given.
        acceleration: f64,
    },
    /// [`Arm::stop`](super::Arm::stop) stopped it, or its future was dropped.
    #[error("the motion was stopped")]
    Stopped,
    /// A newer motion replaced it.
    #[error("a newer motion replaced this one")]
    Replaced,
    /// Its profile ended but the arm did not settle at the target (something blocks it).
    #[error(
        "the arm did not reach {target:?} within {seconds} s of the motion's end; it is at {at:?}"
    )]
    NotArrived {
        /// The target joints.
        target: Joints,
        /// Where the arm is.
        at: Joints,
        /// How long after the motion's end it was given to settle.
        seconds: f64,
    },
    /// A real arm's connection dropped during the motion and was reopened, and the arm did
    /// not reach the target: the controller lost the motion's program (a restart, say).
    #[error(
        "the connection to the arm's controller dropped during the motion and was reopened \
         ({cause}); the controller did not finish the motion (was it restarted?): the arm is at \
         {at:?}, not at {target:?}; move it again"
    )]
    ConnectionLost {
        /// What dropped, and why.
        cause: String,
        /// The target joints.
        target: Joints,
        /// Where the arm is.
        at: Joints,
    },
    /// A real arm's safety system stopped it (a protective stop after a collision, an
    /// emergency stop, …); after a protective stop, inspect the cause, then
    /// [`Arm::unlock_protective_stop`](super::Arm::unlock_protective_stop).
    #[error("the arm's safety system stopped it: {mode}")]
    SafetyStop {
        /// The controller's safety mode (`PROTECTIVE_STOP`, `ROBOT_EMERGENCY_STOP`, …).
        mode: &'static str,
    },
    /// A real arm is not running (its robot mode is `POWER_OFF`, `IDLE` with its brakes
    /// locked, …): power it on and release its brakes on the teach pendant.
    #[error("the arm is not running (robot mode {mode}): power it on and release its brakes")]
    NotRunning {
        /// The controller's robot mode.
        mode: &'static str,
    },
    /// A real arm's streaming program ended on its controller while targets were streamed:
    /// its watchdog saw no target in time, it was stopped on the teach pendant or replaced
    /// by another program, or it never connected back. The arm was stopped.
    #[error("the streaming program on the arm's controller ended: {why}")]
    ProgramStopped {
        /// Why, as far as the driver can tell.
        why: String,
    },
    /// A stream of targets ([`Arm::servo_j`](super::Arm::servo_j)) was ended by `cause` (a
    /// safety stop, the power), and stays ended after the stop clears until it is re-armed
    /// ([`Arm::rearm`](super::Arm::rearm), or an episode's begin): nothing a policy sends
    /// meanwhile reaches the arm.
    #[error(
        "streaming stopped: {cause}; once it is cleared, re-arm the stream (Arm::rearm, or \
         begin an episode) to stream from where the arm is"
    )]
    StreamStopped {
        /// What stopped it.
        cause: Box<MotionError>,
    },
    /// The platform stopped, or a timeout passed.
    #[error(transparent)]
    Wait(#[from] WaitError),
}

impl From<IkError> for MotionError {
    fn from(error: IkError) -> Self {
        Self::Path(PathError::Kinematics(error))
    }
}

impl MotionEnding for MotionError {
    type Joints = Joints;

    fn stopped() -> Self {
        Self::Stopped
    }

    fn replaced() -> Self {
        Self::Replaced
    }

    fn not_arrived(target: Joints, at: Joints, seconds: f64) -> Self {
        Self::NotArrived {
            target,
            at,
            seconds,
        }
    }
}
