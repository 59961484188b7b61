//! [`SerialMotionError`]: why a serial arm's motion did not arrive.

use yarok_core::time::WaitError;

use crate::robots::motions::MotionEnding;

use super::kinematics::SerialIkError;

/// Why a [`SerialArm`](super::SerialArm)'s motion did not arrive.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SerialMotionError {
    /// The target, or a point of the line on the way, cannot be reached; nothing moved.
    #[error("{0}")]
    Unreachable(#[from] SerialIkError),
    /// A point of the line, this far along it (metres or radians), is reached only by a joint
    /// jumping: the line passes a singularity or a limit; nothing moved.
    #[error(
        "the line passes a singularity {along:.3} along its length (a joint would jump {jump:.2} rad)"
    )]
    Singular {
        /// How far along the line.
        along: f64,
        /// The jump (radians or metres).
        jump: f64,
    },
    /// Target joints of the wrong number, not finite, or outside the joint limits; nothing
    /// moved.
    #[error("target joints {target:?} are not one finite angle per joint within its limits")]
    InvalidTarget {
        /// The joints asked for.
        target: Vec<f64>,
    },
    /// A speed or acceleration is not a positive number.
    #[error("speed {speed} and acceleration {acceleration} must be positive numbers")]
    InvalidLimits {
        /// The speed given.
        speed: f64,
        /// The acceleration given.
        acceleration: f64,
    },
    /// [`SerialArm::stop`](super::SerialArm::stop) stopped it, or its future was dropped.
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
        target: Vec<f64>,
        /// Where the arm is.
        at: Vec<f64>,
        /// How long after the motion's end it was given to settle.
        seconds: f64,
    },
    /// The platform stopped, or a timeout passed.
    #[error(transparent)]
    Wait(#[from] WaitError),
}

impl MotionEnding for SerialMotionError {
    type Joints = Vec<f64>;

    fn stopped() -> Self {
        Self::Stopped
    }

    fn replaced() -> Self {
        Self::Replaced
    }

    fn not_arrived(target: Vec<f64>, at: Vec<f64>, seconds: f64) -> Self {
        Self::NotArrived {
            target,
            at,
            seconds,
        }
    }
}
