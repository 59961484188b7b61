//! [`Controller`]: runs an arm's motions as the UR controller does — after every step, the
//! joints due along the motion's path, fed to the servos with their speed and acceleration —
//! and tells how each motion ended.

use std::cell::RefCell;
use std::rc::Rc;

use nalgebra::Isometry3;
use yarok_core::time::Clock;

use crate::robots::motion::{Limits, MotionControl};
use crate::robots::motions::{Motions, Running};

use super::drive::{ArmDrive, Order, Setpoint};
use super::error::MotionError;
use super::kinematics::{IkError, Joints, Kinematics};
use super::path::Path;
use super::payload::Payload;
use crate::robots::profile::Profile;

/// Where a motion goes, and how.
#[derive(Debug, Clone, Copy)]
pub(super) enum Goal {
    Joints(Joints),
    /// In joint space, to the joints that put the TCP at the pose.
    JointsFor(Isometry3<f64>),
    /// The TCP along a straight line.
    Line(Isometry3<f64>),
}

/// Runs an arm's motions.
pub(super) struct Controller {
    kinematics: Kinematics,
    clock: Clock,
    drive: Rc<dyn ArmDrive>,
    state: RefCell<State>,
}

struct State {
    /// What is commanded for the next step, with the payload set by
    /// [`Controller::set_payload`].
    setpoint: Setpoint,
    motions: Motions<Path, Joints, MotionError>,
}

/// The joints `t` seconds into `motion` (by inverse kinematics near `near` on a line), and
/// their speeds over the step of `dt` that follows.
fn reference(
    motion: &Running<Path, Joints>,
    t: f64,
    dt: f64,
    kinematics: &Kinematics,
    near: &Joints,
) -> Result<(Joints, Joints), IkError> {
    let (along, _) = motion.profile.at(t);
    let (ahead, _) = motion.profile.at(t + dt);
    let q = Path::joints_at(motion.path.point(along), kinematics, near)?;
    let next = Path::joints_at(motion.path.point(ahead), kinematics, &q)?;
    Ok((q, std::array::from_fn(|i| (next[i] - q[i]) / dt)))
}

impl Controller {
    /// A controller of `drive`, holding `start` until a motion comes.
    pub(super) fn new(
        clock: Clock,
        kinematics: Kinematics,
        drive: Rc<dyn ArmDrive>,
        start: Joints,
    ) -> Self {
        Self {
            kinematics,
            clock,
            drive,
            state: RefCell::new(State {
                setpoint: Setpoint {
                    q: start,
                    speed: [0.0; 6],
                    acceleration: [0.0; 6],
                    payload: None,
                },
                motions: Motions::new(),
            }),
        }
    }

    pub(super) fn kinematics(&self) -> &Kinematics {
        &self.kinematics
    }

    /// Joint angles (radians).
    pub(super) fn q(&self) -> Joints {
        self.drive.q(&self.state.borrow().setpoint)
    }

    /// Joint speeds (rad/s).
    pub(super) fn qd(&self) -> Joints {
        self.drive.qd(&self.state.borrow().setpoint)
    }

    /// Unlocks a protective stop, where the drive has one.
    pub(super) async fn unlock_protective_stop(&self) -> Result<(), String> {
        self.drive.unlock_protective_stop().await
    }

    /// Whether a motion is under way.
    pub(super) fn is_moving(&self) -> bool {
        self.state.borrow().motions.is_moving()
    }

    /// After a step: the reference for the next one, and whether the motion has ended.
    pub(super) fn tick(&self) {
        self.advance(self.clock.time());
        self.command();
    }

    /// Moves the reference to where the motion is due at `now` plus a step.
    fn advance(&self, now: f64) {
        let mut state = self.state.borrow_mut();
        let Some(motion) = state.motions.take() else {
            return;
        };
        let dt = self.clock.timestep();
        let t = now + dt - motion.started;
        let reference = match self.drive.halt() {
            Some(error) => Err(error),
            None => reference(&motion, t, dt, &self.kinematics, &state.setpoint.q)
                .map_err(MotionError::from),
        };
        let outcome = match reference {
            Err(error) => Some(Err(error)),
            Ok((q, speed)) => {
                let setpoint = &mut state.setpoint;
                let before = setpoint.q;
                setpoint.acceleration =
                    std::array::from_fn(|i| (speed[i] - (q[i] - before[i]) / dt) / dt);
                setpoint.q = q;
                setpoint.speed = speed;
                // A real arm's position not yet current is known again, or the run ends.
                if t >= motion.profile.duration() && self.drive.is_current() {
                    motion
                        .settled(self.drive.q(&state.setpoint), now)
                        .map(|outcome| outcome.map_err(|miss| self.explained(miss)))
                } else {
                    None
                }
            }
        };
        match outcome {
            Some(outcome) => {
                state.setpoint.speed = [0.0; 6];
                state.setpoint.acceleration = [0.0; 6];
                state.motions.end(motion, outcome);
            }
            None => state.motions.keep(motion),
        }
    }

    /// `miss` as the drive explains it: a motion whose connection dropped on the way is lost
    /// to that, not merely short of its target.
    fn explained(&self, miss: MotionError) -> MotionError {
        match (miss, self.drive.interruption()) {
            (MotionError::NotArrived { target, at, .. }, Some(cause)) => {
                MotionError::ConnectionLost { cause, target, at }
            }
            (miss, _) => miss,
        }
    }

    /// The world went back to its start (an episode began): the arm holds `start` again, and a
    /// motion under way ends as stopped.
    pub(super) fn restart(&self, start: Joints) {
        self.hold(start);
        self.command();
    }

    /// Ends a motion under way as stopped and holds `q` at rest.
    fn hold(&self, q: Joints) {
        let mut state = self.state.borrow_mut();
        state.motions.abandon();
        let setpoint = &mut state.setpoint;
        setpoint.q = q;
        setpoint.speed = [0.0; 6];
        setpoint.acceleration = [0.0; 6];
    }

    /// Holds `target` from the next step, as URScript's `servoj` streamed every `seconds`
    /// does: a motion under way ends as stopped, and the servos are set to the target at once.
    pub(super) fn servo(&self, target: Joints, seconds: f64) -> Result<(), MotionError> {
        self.joint_path(target, target)?;
        self.hold(target);
        self.drive.order(Order::ServoJ { target, seconds });
        self.command();
        Ok(())
    }

    /// The joints commanded for the next step.
    pub(super) fn setpoint(&self) -> Joints {
        self.state.borrow().setpoint.q
    }

    /// Commands the setpoint to the drive.
    pub(super) fn command(&self) {
        self.drive.command(&self.state.borrow().setpoint);
    }

    /// Sets what the arm carries: fed forward in `sim`, ordered of a real arm.
    pub(super) fn set_payload(&self, payload: Payload) {
        self.state.borrow_mut().setpoint.payload = Some(payload);
        self.drive.order(Order::SetPayload(payload));
        self.command();
    }

    fn joint_path(&self, from: Joints, target: Joints) -> Result<Path, MotionError> {
        let inside = target
            .iter()
            .zip(&self.kinematics.limits)
            .all(|(q, (lower, upper))| q.is_finite() && (lower..=upper).contains(&q));
        if inside {
            Ok(Path::Joints { from, to: target })
        } else {
            Err(MotionError::InvalidTarget { target })
        }
    }
}

impl MotionControl for Controller {
    type Goal = Goal;
    type Error = MotionError;

    /// Starts a motion to `to`, after checking the whole path; its id.
    fn start(&self, goal: Self::Goal, limits: Limits) -> Result<u64, MotionError> {
        let Limits {
            speed,
            acceleration,
            ..
        } = limits;
        if !(speed > 0.0 && acceleration > 0.0 && speed.is_finite() && acceleration.is_finite()) {
            return Err(MotionError::InvalidLimits {
                speed,
                acceleration,
            });
        }
        let mut state = self.state.borrow_mut();
        let from = state.setpoint.q;
        let path = match goal {
            Goal::Joints(target) => self.joint_path(from, target)?,
            Goal::JointsFor(pose) => {
                self.joint_path(from, self.kinematics.nearest(&pose, &from)?)?
            }
            Goal::Line(pose) => Path::Line {
                from: self.kinematics.forward(&from),
                to: pose,
            },
        };
        let target = path.check(&self.kinematics, &from)?;
        let profile = Profile::rest_to_rest(path.length(), speed, acceleration);
        let id = state
            .motions
            .start(path, profile, self.clock.time(), target);
        drop(state);
        self.drive.order(match path {
            Path::Line { to, .. } => Order::MoveL {
                pose: to,
                tcp: self.kinematics.tcp,
                speed,
                acceleration,
            },
            Path::Joints { .. } => Order::MoveJ {
                target,
                speed,
                acceleration,
            },
        });
        self.advance(self.clock.time());
        self.command();
        Ok(id)
    }

    /// Stops the motion under way (only motion `id`, if given).
    fn stop(&self, id: Option<u64>) {
        let mut state = self.state.borrow_mut();
        if let Some(motion) = state.motions.stop(id, self.clock.time()) {
            let deceleration = motion.profile.acceleration();
            self.drive.order(match motion.path {
                Path::Line { .. } => Order::StopL { deceleration },
                Path::Joints { .. } => Order::StopJ { deceleration },
            });
        }
    }

    /// How motion `id` is: `None` while under way.
    fn outcome(&self, id: u64) -> Option<Result<(), MotionError>> {
        self.state.borrow().motions.outcome(id)
    }

    fn clock(&self) -> &Clock {
        &self.clock
    }
}
