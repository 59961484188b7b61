//! [`Controller`]: runs a serial arm's motions in `sim` as a real arm's controller does — after
//! every step, the joints due along the motion's path, with the forces their accelerations,
//! gravity and the rest of the bias take fed forward — and tells how each motion ended.

use std::cell::RefCell;

use nalgebra::Isometry3;
use yarok_core::time::Clock;

use crate::robots::motion::{Limits, MotionControl};
use crate::robots::motions::Motions;
use crate::robots::paths;
use crate::robots::profile::Profile;
use yarok_mjc::{ConstraintSource, Joint, JointLosses};

use super::actuated_joints::{ActuatedJoint, ActuatedJoints, Actuation};
use super::dynamics::Dynamics;
use super::error::{SerialMotionError, StuckCause};
use super::kinematics::{SerialIkError, SerialKinematics};

/// Where a motion goes.
#[derive(Debug, Clone)]
pub(super) enum Goal {
    Joints(Vec<f64>),
    /// In joint space, to the joints nearest the current ones that put the TCP at the pose.
    JointsFor(Isometry3<f64>),
    /// The TCP along a straight line.
    Line(Isometry3<f64>),
}

/// A motion's path, measured by the length its profile runs along.
#[derive(Debug, Clone)]
enum Path {
    /// Every joint moves in proportion; the length is the largest joint motion.
    Joints { from: Vec<f64>, to: Vec<f64> },
    /// The TCP along a line while turning; the length is the longer of distance and turn.
    Line {
        from: Isometry3<f64>,
        to: Isometry3<f64>,
        /// The joints at the start, which the redundant joints are drawn back to.
        posture: Vec<f64>,
    },
}

impl Path {
    fn length(&self) -> f64 {
        match self {
            Path::Joints { from, to } => paths::joints_length(from, to),
            Path::Line { from, to, .. } => paths::line_length(from, to),
        }
    }

    /// The joints `along` the path, found near `near` on a line.
    fn joints_at(
        &self,
        along: f64,
        kinematics: &mut SerialKinematics,
        near: &[f64],
    ) -> Result<Vec<f64>, SerialMotionError> {
        let fraction = paths::fraction(along, self.length());
        match self {
            Path::Joints { from, to } => Ok(from
                .iter()
                .zip(to)
                .map(|(a, b)| a + (b - a) * fraction)
                .collect()),
            Path::Line { from, to, posture } => {
                Ok(kinematics.solve_towards(&from.lerp_slerp(to, fraction), near, posture)?)
            }
        }
    }

    /// Checks, before anything moves, that the arm can follow the whole path from `start`;
    /// the joints at each point checked, from the start to the end.
    fn check(
        &self,
        kinematics: &mut SerialKinematics,
        start: &[f64],
    ) -> Result<Vec<(f64, Vec<f64>)>, SerialMotionError> {
        let length = self.length();
        paths::check(
            length,
            matches!(self, Path::Line { .. }),
            start.to_vec(),
            |along, near| {
                self.joints_at(along, kinematics, near)
                    .map_err(|error| match error {
                        SerialMotionError::Unreachable(SerialIkError::Unreachable {
                            metres,
                            radians,
                        }) if along < length => SerialMotionError::LeavesReach {
                            along,
                            length,
                            metres,
                            radians,
                        },
                        other => other,
                    })
            },
            |along, jump| SerialMotionError::Singular {
                along,
                length,
                jump,
            },
        )
    }
}

/// A joint speed (rad/s or m/s) below which the arm counts as still.
const STILL: f64 = 0.01;

/// How much the defaults' speed and acceleration are lowered at a time, when an arm cannot
/// follow them, and how many times at most.
const SLOWER: f64 = 0.8;
const SLOWER_TIMES: usize = 20;

struct State {
    reference: Vec<f64>,
    speed: Vec<f64>,
    acceleration: Vec<f64>,
    /// Each motor's integrated tracking error (an acceleration, given through the inertia):
    /// what holds the joint against what the model and the feed-forward do not include. Kept
    /// within what the motor can give.
    integral: Vec<f64>,
    /// Each motor's saturation in the last command: the force asked beyond its range (0 when
    /// within).
    saturation: Vec<f64>,
    /// The worst saturation of the motion under way: which joint, and the force asked.
    strain: Option<(usize, f64)>,
    motions: Motions<Path, Vec<f64>, SerialMotionError>,
}

/// Runs a serial arm's motions.
pub(super) struct Controller {
    kinematics: RefCell<SerialKinematics>,
    dynamics: RefCell<Dynamics>,
    clock: Clock,
    drives: ActuatedJoints,
    /// The drives' joints, in their order.
    joints: Vec<Joint>,
    /// How stiffly motors track (rad/s, the natural frequency of the tracking error).
    stiffness: f64,
    state: RefCell<State>,
}

impl Controller {
    pub(super) fn new(
        clock: Clock,
        kinematics: SerialKinematics,
        dynamics: Dynamics,
        drives: ActuatedJoints,
        stiffness: f64,
        start: Vec<f64>,
    ) -> Self {
        let zeros = vec![0.0; start.len()];
        Self {
            kinematics: RefCell::new(kinematics),
            dynamics: RefCell::new(dynamics),
            clock,
            joints: drives.iter().map(|drive| drive.joint.clone()).collect(),
            drives,
            stiffness,
            state: RefCell::new(State {
                reference: start,
                speed: zeros.clone(),
                acceleration: zeros.clone(),
                integral: zeros.clone(),
                saturation: zeros,
                strain: None,
                motions: Motions::new(),
            }),
        }
    }

    pub(super) fn kinematics(&self) -> std::cell::RefMut<'_, SerialKinematics> {
        self.kinematics.borrow_mut()
    }

    pub(super) fn q(&self) -> Vec<f64> {
        self.drives
            .iter()
            .map(|drive| drive.joint.position())
            .collect()
    }

    pub(super) fn qd(&self) -> Vec<f64> {
        self.drives
            .iter()
            .map(|drive| drive.joint.velocity())
            .collect()
    }

    /// Whether a motion is under way or a joint still moves.
    pub(super) fn is_moving(&self) -> bool {
        self.state.borrow().motions.is_moving() || self.qd().iter().any(|v| v.abs() > STILL)
    }

    /// After a step: the reference for the next one, and whether the motion has ended.
    pub(super) fn tick(&self) {
        self.advance(self.clock.time());
        self.integrate();
        self.command();
    }

    /// The inertia each joint's feedback is scaled by: the joint's own (the mass matrix's
    /// diagonal), at least what its damping makes it behave as over the stiffness's time
    /// scale, and at most what one step of explicit feedback keeps stable.
    fn feedback_inertia(&self, drive: &ActuatedJoint) -> f64 {
        let inertia = drive.joint.inertia();
        let damping = drive.losses.damping;
        let dt = self.clock.timestep();
        let stable = (inertia + damping * dt) / (3.0 * self.stiffness * dt);
        inertia
            .max(damping / self.stiffness)
            .min(stable.max(inertia))
    }

    /// The proportional and derivative gains (per second squared, per second) that, with the
    /// integral, place the tracking error's three poles at the stiffness.
    fn gains(&self) -> (f64, f64) {
        (3.0 * self.stiffness * self.stiffness, 3.0 * self.stiffness)
    }

    /// Adds the step's tracking error to each motor's integral, unless the motor is saturated
    /// the way the error would push it (anti-windup).
    fn integrate(&self) {
        let mut state = self.state.borrow_mut();
        let gain = self.stiffness.powi(3) * self.clock.timestep();
        for (i, drive) in self.drives.iter().enumerate() {
            let error = state.reference[i] - drive.joint.position();
            if state.saturation[i] * error > 0.0 {
                continue;
            }
            let most = drive.strength() / self.feedback_inertia(drive);
            state.integral[i] = (state.integral[i] + gain * error).clamp(-most, most);
        }
    }

    fn advance(&self, now: f64) {
        let mut state = self.state.borrow_mut();
        let Some(mut motion) = state.motions.take() else {
            return;
        };
        let dt = self.clock.timestep();
        let t = now + dt - motion.started;
        let mut kinematics = self.kinematics.borrow_mut();
        let (along, _) = motion.profile.at(t);
        let (ahead, _) = motion.profile.at(t + dt);
        let reference = motion
            .path
            .joints_at(along, &mut kinematics, &state.reference)
            .and_then(|q| {
                let next = motion.path.joints_at(ahead, &mut kinematics, &q)?;
                Ok((q, next))
            });
        drop(kinematics);
        let outcome = match reference {
            Err(error) => Some(Err(error)),
            Ok((q, next)) => {
                let speed: Vec<f64> = q.iter().zip(&next).map(|(a, b)| (b - a) / dt).collect();
                state.acceleration = (0..q.len())
                    .map(|i| (speed[i] - (q[i] - state.reference[i]) / dt) / dt)
                    .collect();
                state.reference = q;
                state.speed = speed;
                if t >= motion.profile.duration() {
                    if matches!(motion.path, Path::Line { .. }) && !motion.stopping {
                        // A redundant arm ends a line where its path's solutions lead.
                        motion.target.clone_from(&state.reference);
                    }
                    motion.settled(self.q(), now)
                } else {
                    None
                }
            }
        };
        match outcome {
            Some(outcome) => {
                let outcome = outcome.map_err(|error| self.explained(error, &state));
                state.speed.fill(0.0);
                state.acceleration.fill(0.0);
                state.strain = None;
                state.motions.end(motion, outcome);
            }
            None => state.motions.keep(motion),
        }
    }

    /// A motion that did not arrive, with the joint furthest off and the cause as far as the
    /// controller can tell.
    fn explained(&self, error: SerialMotionError, state: &State) -> SerialMotionError {
        let SerialMotionError::NotArrived {
            target,
            at,
            seconds,
        } = error
        else {
            return error;
        };
        let Some(joint) = (0..target.len()).max_by(|&a, &b| {
            (target[a] - at[a])
                .abs()
                .total_cmp(&(target[b] - at[b]).abs())
        }) else {
            return SerialMotionError::NotArrived {
                target,
                at,
                seconds,
            };
        };
        let drive = &self.drives[joint];
        let off = (target[joint] - at[joint]).abs();
        let (kp, _) = self.gains();
        // The feedback's force there: the proportional and integral terms (accelerations)
        // through the joint's feedback inertia.
        let pushing = (kp * off + state.integral[joint].abs()) * self.feedback_inertia(drive);
        let toward = (target[joint] - at[joint]).signum();
        let cause = match (held_back(drive, toward, pushing), state.strain) {
            (Some(cause), _) => cause,
            (None, Some((strained, asked))) => StuckCause::Saturated {
                joint: self.drives[strained].name.clone(),
                asked,
                range: self.drives[strained].force_range,
            },
            (None, None)
                if drive.losses.frictionloss > 0.0 && pushing < 2.0 * drive.losses.frictionloss =>
            {
                StuckCause::Friction {
                    frictionloss: drive.losses.frictionloss,
                    inertia: drive.joint.inertia(),
                }
            }
            (None, None) => StuckCause::Blocked,
        };
        SerialMotionError::Stuck {
            joint: drive.name.clone(),
            target: target[joint],
            at: at[joint],
            seconds,
            cause,
        }
    }

    /// The world went back to its start: the arm holds `start`, a motion under way is stopped.
    pub(super) fn restart(&self, start: &[f64]) {
        {
            let mut state = self.state.borrow_mut();
            state.motions.abandon();
            state.reference = start.to_vec();
            state.speed.fill(0.0);
            state.acceleration.fill(0.0);
            state.integral.fill(0.0);
            state.saturation.fill(0.0);
            state.strain = None;
        }
        self.command();
    }

    /// Sets the actuators for the reference, with what a real arm's controller adds: the forces
    /// the reference's accelerations take (through the whole inertia matrix), gravity, Coriolis
    /// and centrifugal forces the model does not compensate itself, and the joints' own damping
    /// and dry friction. Motors track with a stiffness of their own (proportional, integral and
    /// derivative terms placing the error's three poles at the stiffness), within what they can
    /// give; servos with the model's gains.
    pub(super) fn command(&self) {
        let mut state = self.state.borrow_mut();
        let (kp, kv) = self.gains();
        let feedback: Vec<f64> = self
            .drives
            .iter()
            .enumerate()
            .map(|(i, drive)| match drive.actuation {
                Actuation::Motor { .. } => {
                    state.integral[i]
                        + kp * (state.reference[i] - drive.joint.position())
                        + kv * (state.speed[i] - drive.joint.velocity())
                }
                Actuation::Servo(_) => 0.0,
            })
            .collect();
        let wanted: Vec<f64> = (0..feedback.len())
            .map(|i| state.acceleration[i] + feedback[i])
            .collect();
        let inertial = Joint::inertial_forces(&self.joints, &wanted);
        for (i, drive) in self.drives.iter().enumerate() {
            let friction = friction_compensation(&drive.losses, wanted[i], drive.joint.velocity());
            let force = inertial[i]
                + drive.joint.bias_force()
                + drive.losses.damping * state.speed[i]
                + friction;
            let control = match drive.actuation {
                Actuation::Motor { gear } => {
                    let extra = self.feedback_inertia(drive) - drive.joint.inertia();
                    let asked = force + extra * feedback[i];
                    let [lower, upper] = drive.force_range;
                    let given = asked.clamp(lower, upper);
                    state.saturation[i] = asked - given;
                    if given != asked
                        && state.motions.is_moving()
                        && state
                            .strain
                            .is_none_or(|(_, worst)| asked.abs() > worst.abs())
                    {
                        state.strain = Some((i, asked));
                    }
                    given / gear
                }
                Actuation::Servo(gains) => {
                    (gains.gear * (gains.kp * state.reference[i] + gains.kv * state.speed[i])
                        + force / gains.gear)
                        / gains.gain
                }
            };
            drive.actuator.set(control);
        }
    }

    /// The motion's profile at `limits`, or, for the defaults, slower until every joint's
    /// actuator can give what it takes.
    fn profile(
        &self,
        points: &[(f64, Vec<f64>)],
        length: f64,
        limits: Limits,
    ) -> Result<Profile, SerialMotionError> {
        let mut dynamics = self.dynamics.borrow_mut();
        let (mut speed, mut acceleration) = (limits.speed, limits.acceleration);
        let mut tries = if limits.chosen { 1 } else { SLOWER_TIMES };
        loop {
            let profile = Profile::rest_to_rest(length, speed, acceleration);
            let Some(overload) = dynamics.overload(points, &profile) else {
                return Ok(profile);
            };
            tries -= 1;
            if tries == 0 {
                return Err(SerialMotionError::Overloaded {
                    joint: self.drives[overload.joint].name.clone(),
                    needed: overload.needed,
                    available: overload.available,
                    speed: overload.speed,
                    chosen: limits.chosen,
                });
            }
            speed *= SLOWER;
            acceleration *= SLOWER;
        }
    }
}

/// The force that cancels a joint's dry friction as MuJoCo models it, for the joint to
/// accelerate at `acceleration` from `velocity` as if it had none: while the friction holds, its
/// soft constraint's force (it makes a light link heavier and damped rather than holding it
/// still); once the joint slides, the friction loss itself.
fn friction_compensation(losses: &JointLosses, acceleration: f64, velocity: f64) -> f64 {
    if losses.frictionloss <= 0.0 {
        return 0.0;
    }
    ((acceleration + losses.friction_damping * velocity) / losses.friction_regularizer)
        .clamp(-losses.frictionloss, losses.frictionloss)
}

impl MotionControl for Controller {
    type Goal = Goal;
    type Error = SerialMotionError;

    /// Starts a motion after checking its whole path, and that every joint's actuator can give
    /// what the motion takes (the defaults are lowered until it can); its id.
    fn start(&self, goal: Self::Goal, limits: Limits) -> Result<u64, SerialMotionError> {
        let Limits {
            speed,
            acceleration,
            ..
        } = limits;
        if !(speed > 0.0 && acceleration > 0.0 && speed.is_finite() && acceleration.is_finite()) {
            return Err(SerialMotionError::InvalidLimits {
                speed,
                acceleration,
            });
        }
        let from = self.state.borrow().reference.clone();
        let mut kinematics = self.kinematics.borrow_mut();
        let path = match goal {
            Goal::Joints(target) => {
                if let Some(error) = kinematics.outside_limits(&target) {
                    return Err(SerialMotionError::InvalidTarget {
                        target,
                        reason: error,
                    });
                }
                Path::Joints { from, to: target }
            }
            Goal::JointsFor(pose) => {
                let target = kinematics.solve(&pose, &from)?;
                Path::Joints { from, to: target }
            }
            Goal::Line(pose) => {
                kinematics.solve(&pose, &from)?;
                Path::Line {
                    from: kinematics.forward(&from),
                    to: pose,
                    posture: from,
                }
            }
        };
        let start = self.state.borrow().reference.clone();
        let points = path.check(&mut kinematics, &start)?;
        drop(kinematics);
        let target = points.last().map_or(start, |(_, end)| end.clone());
        let profile = self.profile(&points, path.length(), limits)?;
        let id = self
            .state
            .borrow_mut()
            .motions
            .start(path, profile, self.clock.time(), target);
        self.state.borrow_mut().strain = None;
        self.advance(self.clock.time());
        self.command();
        Ok(id)
    }

    /// Stops the motion under way (only motion `id`, if given): it decelerates along its path.
    fn stop(&self, id: Option<u64>) {
        let now = self.clock.time();
        self.state.borrow_mut().motions.stop(id, now);
    }

    /// How motion `id` is: `None` while under way.
    fn outcome(&self, id: u64) -> Option<Result<(), SerialMotionError>> {
        self.state.borrow().motions.outcome(id)
    }

    fn clock(&self) -> &Clock {
        &self.clock
    }
}

/// The constraint that holds `drive`'s joint back from moving `toward` (+1 or -1), if one puts
/// a force against it comparable to what drives it: the strongest contact, equality constraint
/// or limit force on the joint opposing the motion, when it is at least a quarter of the
/// actuator's strength or of the controller's push (`pushing`), whichever is less.
fn held_back(drive: &ActuatedJoint, toward: f64, pushing: f64) -> Option<StuckCause> {
    let against = drive
        .joint
        .constraint_forces()
        .into_iter()
        .find(|held| held.force * toward < 0.0 && held.source != ConstraintSource::Friction)?;
    let force = against.force.abs();
    if force < 0.25 * drive.strength().min(pushing) {
        return None;
    }
    Some(match against.source {
        ConstraintSource::Contact {
            bodies,
            normal_force,
            ..
        } => StuckCause::Contact {
            bodies,
            normal_force,
            force,
        },
        ConstraintSource::Equality { index, name } => {
            StuckCause::Constrained { name, index, force }
        }
        ConstraintSource::JointLimit { name, joint } => StuckCause::Limit {
            what: name.map_or_else(
                || format!("joint {}", joint.index()),
                |name| format!("joint {name:?}"),
            ),
            force,
        },
        ConstraintSource::TendonLimit { name, tendon } => StuckCause::Limit {
            what: name.map_or_else(
                || format!("tendon {}", tendon.index()),
                |name| format!("tendon {name:?}"),
            ),
            force,
        },
        _ => return None,
    })
}
