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
        "the line passes a singularity or a joint limit at {percent:.0} % of its length: a joint would jump {jump:.2} rad there",
        percent = 100.0 * along / length
    )]
    Singular {
        /// How far along the line (metres, or radians for a line that turns more than it
        /// moves).
        along: f64,
        /// The line's length (the longer of its distance and its turn).
        length: f64,
        /// The jump (radians or metres).
        jump: f64,
    },
    /// The line's end is within reach, but a point on the way, this far along it, is not (or
    /// is one the solver cannot reach from the point before: a singularity); nothing moved.
    #[error(
        "the line leaves the arm's reach at {percent:.0} % of its length, though its end is within reach: the nearest the arm gets there is {metres:.4} m and {radians:.4} rad from it (a singularity or a joint limit on the way)",
        percent = 100.0 * along / length
    )]
    LeavesReach {
        /// How far along the line (metres, or radians for a line that turns more than it
        /// moves).
        along: f64,
        /// The line's length (the longer of its distance and its turn).
        length: f64,
        /// The distance left there (metres).
        metres: f64,
        /// The rotation left there (radians).
        radians: f64,
    },
    /// Target joints of the wrong number, not finite, or outside the joint limits; nothing
    /// moved.
    #[error("target joints {target:?} cannot be reached: {reason}")]
    InvalidTarget {
        /// The joints asked for.
        target: Vec<f64>,
        /// Which joint, and its limits.
        reason: String,
    },
    /// A joint would need more force than its actuator can give to follow the motion (its
    /// damping at speed, gravity, the inertia accelerated); nothing moved. Only at a speed or
    /// acceleration the user chose: the defaults are lowered until the arm can follow them.
    #[error(
        "joint {joint:?} would need {needed:.1} N·m at {speed:.2} rad/s to follow the motion, more than the {share:.0} % of the {available:.1} N·m its actuator gives that a motion may plan on: {advice}",
        share = 100.0 * super::dynamics::PLANNED_SHARE,
        advice = if *chosen { "ask a lower speed or acceleration, or give the joint a stronger actuator" } else { "the arm cannot hold or move this way at any speed; give the joint a stronger actuator or a lighter load" }
    )]
    Overloaded {
        /// The joint's name.
        joint: String,
        /// The force it would need.
        needed: f64,
        /// What its actuator gives that way.
        available: f64,
        /// The joint's speed then.
        speed: f64,
        /// Whether the user chose the speed and acceleration (or the defaults, lowered as far
        /// as they go, were used).
        chosen: bool,
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
    /// Its profile ended but joint `joint` did not settle at its target; `cause` tells why, as
    /// far as the controller can.
    #[error(
        "joint {joint:?} did not reach {target:.4} within {seconds} s of the motion's end (it is at {at:.4}): {cause}"
    )]
    Stuck {
        /// The joint furthest from its target.
        joint: String,
        /// Its target.
        target: f64,
        /// Where it is.
        at: f64,
        /// How long after the motion's end it was given to settle.
        seconds: f64,
        /// Why, as far as the controller can tell.
        cause: StuckCause,
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

/// Why a joint did not settle at its target ([`SerialMotionError::Stuck`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StuckCause {
    /// An actuator was saturated during the motion: it was asked more than it gives.
    #[error(
        "the actuator of joint {joint:?} was saturated, asked {asked:.1} N·m of its range [{}, {}]: ask a lower speed or acceleration, or give the joint a stronger actuator",
        range[0], range[1]
    )]
    Saturated {
        /// The joint whose actuator was asked the most beyond its range.
        joint: String,
        /// The force asked.
        asked: f64,
        /// What the actuator gives.
        range: [f64; 2],
    },
    /// The joint's dry friction holds it against what the controller gives so close to the
    /// target: a light link (little inertia to push against) on a joint with friction.
    #[error(
        "its dry friction (frictionloss {frictionloss} N·m) holds it against what the controller gives so near the target, its link being light (inertia {inertia:.2e} kg·m²): mount the tool it is made to carry, or raise the stiffness"
    )]
    Friction {
        /// The joint's `frictionloss`.
        frictionloss: f64,
        /// The inertia the joint moves.
        inertia: f64,
    },
    /// A contact holds it back: the arm presses on something, or something on it.
    #[error(
        "a contact between {} and {} holds it back ({normal_force:.0} N between them, {force:.1} N·m against the joint): clear the way or move around it",
        bodies[0], bodies[1]
    )]
    Contact {
        /// The two bodies in contact.
        bodies: [String; 2],
        /// The normal force between them (newtons).
        normal_force: f64,
        /// The force the contact puts against the joint (N·m, or N for a slide).
        force: f64,
    },
    /// An equality constraint of the model (a weld, a connect, a coupling) holds it back.
    #[error(
        "the equality constraint {} holds it back ({force:.1} N·m against the joint): the model ties the arm there; move where the constraint lets it, or leave the constraint out",
        name.as_deref().map_or_else(|| format!("number {index}"), |name| format!("{name:?}"))
    )]
    Constrained {
        /// The constraint's name, if it has one.
        name: Option<String>,
        /// Its index among the model's equality constraints.
        index: usize,
        /// The force it puts against the joint.
        force: f64,
    },
    /// A joint or tendon limit of the model holds it back (a limit's `margin` reaches before
    /// the range's end).
    #[error(
        "the limit of {what} holds it back ({force:.1} N·m against the joint): stay further inside its range (the model's limit margin reaches before the range's end)"
    )]
    Limit {
        /// The limited joint or tendon, named.
        what: String,
        /// The force the limit puts against the joint.
        force: f64,
    },
    /// Nothing the controller knows of: a load heavier than the model's.
    #[error("something blocks it (a load the model does not have)")]
    Blocked,
}
