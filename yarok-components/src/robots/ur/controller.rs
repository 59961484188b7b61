//! [`Controller`]: runs an arm's motions as the UR controller does — after every step, the
//! joints due along the motion's path, fed to the servos with their speed and acceleration —
//! and tells how each motion ended.

use std::cell::RefCell;
use std::rc::Rc;

use nalgebra::{Isometry3, Point3};
use yarok_core::time::Clock;
use yarok_mjc::{Actuator, Joint, ServoGains, Site};

use super::error::MotionError;
use super::kinematics::{IkError, Joints, Kinematics, pose_to_vector};
use super::measured::isometry_of;
use super::path::Path;
use super::payload::Payload;
use super::real::RealLink;
use crate::robots::profile::Profile;
use yarok_hw::ur::script;

/// How close (radians, every joint) counts as arrived.
pub const ARRIVED_RAD: f64 = 1e-3;

/// Seconds after its profile ends that a motion may take to settle within [`ARRIVED_RAD`]
/// before it counts as failed (something blocks the arm).
pub const SETTLE_SECONDS: f64 = 0.5;

/// Seconds a real arm's stream may take to show an unlocked protective stop cleared.
const UNLOCKED_SECONDS: f64 = 2.0;

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
    drive: Drive,
    state: RefCell<State>,
}

/// What the motions move.
pub(super) enum Drive {
    Sim(Box<Servos>),
    /// Follows the reference exactly.
    Mock,
    /// A real arm: each motion goes to its controller as URScript, which moves the arm; the
    /// motion's profile here tells when it should have arrived.
    Real(Rc<RealLink>),
}

/// The joints and position servos of an arm in `sim`, with the servos' gains as the model
/// states them, its flange site and the world's gravity (for the payload).
pub(super) struct Servos {
    pub(super) joints: [Joint; 6],
    pub(super) servos: [Actuator; 6],
    pub(super) gains: [ServoGains; 6],
    pub(super) flange: Site,
    pub(super) gravity: [f64; 3],
}

impl Servos {
    /// What each joint must give to hold `payload` against gravity.
    fn holding(&self, payload: &Payload) -> Vec<f64> {
        let centre = isometry_of(&self.flange.pose()) * Point3::from(payload.centre);
        let weight = self.gravity.map(|g| -g * payload.mass);
        self.flange
            .forces_on(&self.joints, centre.coords.into(), weight)
    }
}

struct State {
    /// The joints and speeds commanded for the next step.
    reference: Joints,
    speed: Joints,
    acceleration: Joints,
    motion: Option<Motion>,
    /// What the arm carries, as set with [`Controller::set_payload`].
    payload: Option<Payload>,
    next_id: u64,
    /// How the last motion that ended, ended.
    ended: Option<(u64, Result<(), MotionError>)>,
}

struct Motion {
    id: u64,
    path: Path,
    profile: Profile,
    /// Platform time at which the profile starts.
    started: f64,
    target: Joints,
    stopping: bool,
}

impl Motion {
    /// The joints `t` seconds into the motion (by inverse kinematics near `near` on a line),
    /// and their speeds over the step of `dt` that follows.
    fn reference(
        &self,
        t: f64,
        dt: f64,
        kinematics: &Kinematics,
        near: &Joints,
    ) -> Result<(Joints, Joints), IkError> {
        let (along, _) = self.profile.at(t);
        let (ahead, _) = self.profile.at(t + dt);
        let q = Path::joints_at(self.path.point(along), kinematics, near)?;
        let next = Path::joints_at(self.path.point(ahead), kinematics, &q)?;
        Ok((q, std::array::from_fn(|i| (next[i] - q[i]) / dt)))
    }
}

impl Controller {
    /// A controller of `drive`, holding `start` until a motion comes.
    pub(super) fn new(clock: Clock, kinematics: Kinematics, drive: Drive, start: Joints) -> Self {
        Self {
            kinematics,
            clock,
            drive,
            state: RefCell::new(State {
                reference: start,
                speed: [0.0; 6],
                acceleration: [0.0; 6],
                motion: None,
                payload: None,
                next_id: 0,
                ended: None,
            }),
        }
    }

    pub(super) fn kinematics(&self) -> &Kinematics {
        &self.kinematics
    }

    pub(super) fn clock(&self) -> &Clock {
        &self.clock
    }

    /// Joint angles (radians).
    pub(super) fn q(&self) -> Joints {
        self.measured(&self.state.borrow())
    }

    /// Joint speeds (rad/s).
    pub(super) fn qd(&self) -> Joints {
        match &self.drive {
            Drive::Sim(sim) => sim.joints.each_ref().map(Joint::velocity),
            Drive::Mock => self.state.borrow().speed,
            Drive::Real(link) => link.qd(),
        }
    }

    /// Unlocks a real arm's protective stop; nothing to do otherwise.
    pub(super) async fn unlock_protective_stop(&self) -> Result<(), String> {
        let Drive::Real(link) = &self.drive else {
            return Ok(());
        };
        link.unlock_protective_stop().await?;
        // Motions may start once the arm's own stream says so.
        self.clock
            .wait(|| link.safety_stop().is_none())
            .timeout(UNLOCKED_SECONDS)
            .await
            .map_err(|e| format!("the safety stop did not clear: {e}"))
    }

    /// Whether a motion is under way.
    pub(super) fn is_moving(&self) -> bool {
        self.state.borrow().motion.is_some()
    }

    /// After a step: the reference for the next one, and whether the motion has ended.
    pub(super) fn tick(&self) {
        self.advance(self.clock.time());
        self.command();
    }

    /// Moves the reference to where the motion is due at `now` plus a step.
    fn advance(&self, now: f64) {
        let mut state = self.state.borrow_mut();
        let Some(motion) = state.motion.take() else {
            return;
        };
        let dt = self.clock.timestep();
        let t = now + dt - motion.started;
        let halt = match &self.drive {
            Drive::Real(link) => link.halt(),
            _ => None,
        };
        let reference = match halt {
            Some(error) => Err(error),
            None => motion
                .reference(t, dt, &self.kinematics, &state.reference)
                .map_err(MotionError::from),
        };
        let outcome = match reference {
            Err(error) => Some(Err(error)),
            Ok((q, speed)) => {
                let before = state.reference;
                state.acceleration =
                    std::array::from_fn(|i| (speed[i] - (q[i] - before[i]) / dt) / dt);
                state.reference = q;
                state.speed = speed;
                if t >= motion.profile.duration() {
                    self.settled(&motion, now, &state)
                } else {
                    None
                }
            }
        };
        match outcome {
            Some(outcome) => {
                state.speed = [0.0; 6];
                state.acceleration = [0.0; 6];
                state.ended = Some((motion.id, outcome));
            }
            None => state.motion = Some(motion),
        }
    }

    /// How a motion whose profile is over ends: `None` while the arm settles.
    fn settled(&self, motion: &Motion, now: f64, state: &State) -> Option<Result<(), MotionError>> {
        let at = self.measured(state);
        if matches!(&self.drive, Drive::Real(link) if link.is_stale()) {
            // RTDE is being reconnected: where the arm is will be known again, or the run ends.
            None
        } else if motion.stopping {
            Some(Err(MotionError::Stopped))
        } else if within(&at, &motion.target) {
            Some(Ok(()))
        } else if now - (motion.started + motion.profile.duration()) > SETTLE_SECONDS {
            Some(Err(MotionError::NotArrived {
                target: motion.target,
                at,
                seconds: SETTLE_SECONDS,
            }))
        } else {
            None
        }
    }

    fn measured(&self, state: &State) -> Joints {
        match &self.drive {
            Drive::Sim(sim) => sim.joints.each_ref().map(Joint::position),
            Drive::Mock => state.reference,
            Drive::Real(link) => link.q(),
        }
    }

    /// The world went back to its start (an episode began): the arm holds `start` again, and a
    /// motion under way ends as stopped.
    pub(super) fn restart(&self, start: Joints) {
        {
            let mut state = self.state.borrow_mut();
            if let Some(motion) = state.motion.take() {
                state.ended = Some((motion.id, Err(MotionError::Stopped)));
            }
            state.reference = start;
            state.speed = [0.0; 6];
            state.acceleration = [0.0; 6];
        }
        self.command();
    }

    /// Sets the servos to the reference, with what the arm's controller adds as a real one
    /// does: the force that the reference's speed and acceleration take and that gravity,
    /// Coriolis and centrifugal forces ask of each joint (those the model does not compensate
    /// itself), and the payload's weight, so that the joints track without lag or sag.
    pub(super) fn command(&self) {
        if let Drive::Sim(sim) = &self.drive {
            let state = self.state.borrow();
            let payload = match &state.payload {
                Some(payload) if payload.mass > 0.0 => sim.holding(payload),
                _ => vec![0.0; 6],
            };
            for (i, gains) in sim.gains.iter().enumerate() {
                let joint = &sim.joints[i];
                let torque =
                    joint.inertia() * state.acceleration[i] + joint.bias_force() + payload[i];
                // The servo's force is gain·ctrl − kp·gear·q − kv·gear·q̇; the joint feels gear
                // times it.
                let force = gains.gear
                    * (gains.kp * state.reference[i] + gains.kv * state.speed[i])
                    + torque / gains.gear;
                sim.servos[i].set(force / gains.gain);
            }
        }
    }

    /// Sets what the arm carries: fed forward in `sim`, sent as `set_payload` to a real arm.
    pub(super) fn set_payload(&self, payload: Payload) {
        self.state.borrow_mut().payload = Some(payload);
        if let Drive::Real(link) = &self.drive {
            link.send_script(script::set_payload(payload.mass, payload.centre));
        }
        self.command();
    }

    /// Starts a motion to `to`, after checking the whole path; its id.
    pub(super) fn start(
        &self,
        goal: Goal,
        speed: f64,
        acceleration: f64,
    ) -> Result<u64, MotionError> {
        if !(speed > 0.0 && acceleration > 0.0 && speed.is_finite() && acceleration.is_finite()) {
            return Err(MotionError::InvalidLimits {
                speed,
                acceleration,
            });
        }
        let mut state = self.state.borrow_mut();
        let from = state.reference;
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
        let id = state.next_id;
        state.next_id += 1;
        if let Some(replaced) = state.motion.take() {
            state.ended = Some((replaced.id, Err(MotionError::Replaced)));
        }
        state.motion = Some(Motion {
            id,
            path,
            profile: Profile::rest_to_rest(path.length(), speed, acceleration),
            started: self.clock.time(),
            target,
            stopping: false,
        });
        drop(state);
        if let Drive::Real(link) = &self.drive {
            link.send_script(match path {
                Path::Line { to, .. } => script::movel_with_tcp(
                    &pose_to_vector(&to),
                    &pose_to_vector(&self.kinematics.tcp),
                    speed,
                    acceleration,
                ),
                Path::Joints { .. } => script::movej(&target, speed, acceleration),
            });
        }
        self.advance(self.clock.time());
        self.command();
        Ok(id)
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

    /// Stops the motion under way (only motion `id`, if given).
    pub(super) fn stop(&self, id: Option<u64>) {
        let mut state = self.state.borrow_mut();
        let now = self.clock.time();
        let Some(motion) = state.motion.as_mut() else {
            return;
        };
        if motion.stopping || id.is_some_and(|id| id != motion.id) {
            return;
        }
        let (along, speed) = motion.profile.at(now - motion.started);
        let deceleration = motion.profile.acceleration();
        if let Drive::Real(link) = &self.drive {
            link.send_script(match motion.path {
                Path::Line { .. } => script::stopl(deceleration),
                Path::Joints { .. } => script::stopj(deceleration),
            });
        }
        motion.profile = Profile::stopping(along, speed, deceleration);
        motion.started = now;
        motion.stopping = true;
    }

    /// How motion `id` is: `None` while under way.
    pub(super) fn outcome(&self, id: u64) -> Option<Result<(), MotionError>> {
        let state = self.state.borrow();
        match (&state.motion, &state.ended) {
            (Some(motion), _) if motion.id == id => None,
            (_, Some((ended, outcome))) if *ended == id => Some(outcome.clone()),
            _ => Some(Err(MotionError::Replaced)),
        }
    }
}

pub(super) fn within(q: &Joints, target: &Joints) -> bool {
    q.iter()
        .zip(target)
        .all(|(a, b)| (a - b).abs() < ARRIVED_RAD)
}
