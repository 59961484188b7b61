//! [`ArmDrive`]: what an arm's motions move in one environment.

use std::future::Future;
use std::pin::Pin;

use nalgebra::Isometry3;

use super::error::MotionError;
use super::kinematics::Joints;
use super::payload::Payload;

/// What the arm's controller wants of the joints over the next step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setpoint {
    /// Joint angles (radians).
    pub q: Joints,
    /// Joint speeds (rad/s).
    pub speed: Joints,
    /// Joint accelerations (rad/s²).
    pub acceleration: Joints,
    /// What the arm carries, once set.
    pub payload: Option<Payload>,
}

/// A motion, a stop or a payload as an arm's own controller is told it (URScript).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Order {
    /// `movej` to `target` (the joint moving furthest at `speed` and `acceleration`).
    MoveJ {
        /// Joint angles (radians).
        target: Joints,
        /// rad/s.
        speed: f64,
        /// rad/s².
        acceleration: f64,
    },
    /// `movel` of the TCP, which is `tcp` in the flange frame, to `pose` in the base frame.
    MoveL {
        /// Where the TCP goes, in the base frame.
        pose: Isometry3<f64>,
        /// The TCP in the flange frame.
        tcp: Isometry3<f64>,
        /// m/s.
        speed: f64,
        /// m/s².
        acceleration: f64,
    },
    /// `servoj` to `target`: the joints follow a streamed target (a policy's actions), each
    /// reached within `seconds`.
    ServoJ {
        /// Joint angles (radians).
        target: Joints,
        /// The time the target is reached in: the streaming period.
        seconds: f64,
        /// Each joint's speed limit (rad/s), for an arm's own controller to hold as well.
        max_speed: Joints,
    },
    /// `stopj`: a joint motion decelerates to a stop.
    StopJ {
        /// rad/s².
        deceleration: f64,
    },
    /// `stopl`: a line decelerates to a stop, staying on it.
    StopL {
        /// m/s².
        deceleration: f64,
    },
    /// `set_payload`.
    SetPayload(Payload),
}

/// The joints of an [`Arm`](super::Arm) in one environment: the simulated servos, a mock, a
/// real arm's controller, or a user's own (a replay, another simulator). The arm's controller
/// runs the motions the same over any: after every step it asks the drive where the joints
/// are, and commands the joints due next.
///
/// # Examples
///
/// A replay: the joints are where a recording says they were.
///
/// ```
/// use yarok_components::robots::ur::{ArmDrive, Joints, Setpoint};
/// use yarok_core::time::Clock;
///
/// struct Replayed {
///     clock: Clock,
///     track: Vec<(f64, Joints)>,
/// }
///
/// impl ArmDrive for Replayed {
///     fn q(&self, _commanded: &Setpoint) -> Joints {
///         let now = self.clock.time();
///         let passed = self.track.iter().take_while(|(time, _)| *time <= now);
///         passed.last().map_or([0.0; 6], |(_, q)| *q)
///     }
///
///     fn qd(&self, _commanded: &Setpoint) -> Joints {
///         [0.0; 6]
///     }
/// }
/// ```
pub trait ArmDrive {
    /// Where the joints are (radians) after the latest step, given the setpoint last
    /// commanded: what the drive measures, or the setpoint's own where it measures nothing (a
    /// mock).
    fn q(&self, commanded: &Setpoint) -> Joints;

    /// The joints' speeds (rad/s), as [`ArmDrive::q`].
    fn qd(&self, commanded: &Setpoint) -> Joints;

    /// Holds the joints to `setpoint`: called after every step and whenever the setpoint
    /// changes. By default nothing (an arm whose own controller runs its orders).
    fn command(&self, setpoint: &Setpoint) {
        let _ = setpoint;
    }

    /// A motion, stop or payload the arm was given, for an arm whose own controller runs it.
    /// By default nothing (the setpoints say it all).
    fn order(&self, order: Order) {
        let _ = order;
    }

    /// Why the arm cannot move now (its safety system stopped it, it is powered off), if so:
    /// the motion under way ends with it.
    fn halt(&self) -> Option<MotionError> {
        None
    }

    /// What cut the motion under way short, if the drive knows: a real arm's connection that
    /// dropped and was reopened since the last order (its controller restarted, and the
    /// order's program with it). A motion that misses its target ends with it instead of a
    /// plain miss. By default nothing.
    fn interruption(&self) -> Option<String> {
        None
    }

    /// Whether [`ArmDrive::q`] is where the arm is now; `false` while it cannot be known (a
    /// dropped stream being reconnected), and a motion waits to end.
    fn is_current(&self) -> bool {
        true
    }

    /// Whether the world puts these joints back at their start when an episode begins (a
    /// simulation does; hardware stays where it is).
    fn is_put_back_at_restart(&self) -> bool {
        false
    }

    /// A stream of targets that a stop ended was re-armed ([`Arm::rearm`](super::Arm::rearm),
    /// or an episode began): a halt the drive reported for the stream alone (a real arm's
    /// streaming program that ended) is cleared. By default nothing.
    fn rearm(&self) {}

    /// Unlocks a protective stop and waits until the arm may move again. By default there is
    /// nothing to unlock.
    fn unlock_protective_stop(&self) -> Pin<Box<dyn Future<Output = Result<(), String>> + '_>> {
        Box::pin(std::future::ready(Ok(())))
    }
}
