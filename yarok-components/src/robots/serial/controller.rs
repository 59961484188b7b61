//! [`Controller`]: runs a serial arm's motions in `sim` as a real arm's controller does — after
//! every step, the joints due along the motion's path, with the forces their accelerations,
//! gravity and the rest of the bias take fed forward — and tells how each motion ended.

use std::cell::RefCell;

use nalgebra::Isometry3;
use yarok_core::time::Clock;

use crate::robots::motion::MotionControl;
use crate::robots::motions::Motions;
use crate::robots::paths;
use yarok_mjc::{Actuator, Joint, ServoGains};

use super::error::SerialMotionError;
use super::kinematics::SerialKinematics;
use crate::robots::profile::Profile;

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
    /// the joints at its end.
    fn check(
        &self,
        kinematics: &mut SerialKinematics,
        start: &[f64],
    ) -> Result<Vec<f64>, SerialMotionError> {
        paths::check(
            self.length(),
            matches!(self, Path::Line { .. }),
            start.to_vec(),
            |along, near| self.joints_at(along, kinematics, near),
            |along, jump| SerialMotionError::Singular { along, jump },
        )
    }
}

/// How an actuator moves its joint.
#[derive(Debug, Clone, Copy)]
pub(super) enum Actuation {
    /// A torque motor: force = gear × control.
    Motor { gear: f64 },
    /// A position servo.
    Servo(ServoGains),
}

/// The joints and actuators of an arm in `sim`, and how stiffly motors track (rad/s).
pub(super) struct SimJoints {
    pub(super) joints: Vec<Joint>,
    pub(super) actuators: Vec<(Actuator, Actuation)>,
    pub(super) stiffness: f64,
}

struct State {
    reference: Vec<f64>,
    speed: Vec<f64>,
    acceleration: Vec<f64>,
    /// Each motor's integrated tracking error (an acceleration): what holds the joint against
    /// what the model's bias forces do not include (dry friction, damping).
    integral: Vec<f64>,
    motions: Motions<Path, Vec<f64>, SerialMotionError>,
}

/// Runs a serial arm's motions.
pub(super) struct Controller {
    kinematics: RefCell<SerialKinematics>,
    clock: Clock,
    sim: SimJoints,
    state: RefCell<State>,
}

impl Controller {
    pub(super) fn new(
        clock: Clock,
        kinematics: SerialKinematics,
        sim: SimJoints,
        start: Vec<f64>,
    ) -> Self {
        let zeros = vec![0.0; start.len()];
        Self {
            kinematics: RefCell::new(kinematics),
            clock,
            sim,
            state: RefCell::new(State {
                reference: start,
                speed: zeros.clone(),
                acceleration: zeros.clone(),
                integral: zeros,
                motions: Motions::new(),
            }),
        }
    }

    pub(super) fn kinematics(&self) -> std::cell::RefMut<'_, SerialKinematics> {
        self.kinematics.borrow_mut()
    }

    pub(super) fn q(&self) -> Vec<f64> {
        self.sim.joints.iter().map(Joint::position).collect()
    }

    pub(super) fn qd(&self) -> Vec<f64> {
        self.sim.joints.iter().map(Joint::velocity).collect()
    }

    pub(super) fn is_moving(&self) -> bool {
        self.state.borrow().motions.is_moving()
    }

    /// After a step: the reference for the next one, and whether the motion has ended.
    pub(super) fn tick(&self) {
        self.advance(self.clock.time());
        self.integrate();
        self.command();
    }

    /// Adds the step's tracking error to each motor's integral.
    fn integrate(&self) {
        let mut state = self.state.borrow_mut();
        let gain = self.sim.stiffness.powi(3) * self.clock.timestep();
        for (i, joint) in self.sim.joints.iter().enumerate() {
            let error = state.reference[i] - joint.position();
            state.integral[i] += gain * error;
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
                state.speed.fill(0.0);
                state.acceleration.fill(0.0);
                state.motions.end(motion, outcome);
            }
            None => state.motions.keep(motion),
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
        }
        self.command();
    }

    /// Sets the actuators for the reference, with what a real arm's controller adds: the forces
    /// the reference's accelerations take (through the whole inertia matrix), and gravity,
    /// Coriolis and centrifugal forces the model does not compensate itself. Motors track with
    /// a stiffness of their own (proportional, integral and derivative terms placing the
    /// error's three poles at the stiffness); servos with the model's gains.
    pub(super) fn command(&self) {
        let state = self.state.borrow();
        let sim = &self.sim;
        let (kp, kv) = (3.0 * sim.stiffness * sim.stiffness, 3.0 * sim.stiffness);
        let wanted: Vec<f64> = sim
            .joints
            .iter()
            .zip(&sim.actuators)
            .enumerate()
            .map(|(i, (joint, (_, actuation)))| match actuation {
                Actuation::Motor { .. } => {
                    state.acceleration[i]
                        + state.integral[i]
                        + kp * (state.reference[i] - joint.position())
                        + kv * (state.speed[i] - joint.velocity())
                }
                Actuation::Servo(_) => state.acceleration[i],
            })
            .collect();
        let inertial = Joint::inertial_forces(&sim.joints, &wanted);
        for (i, (joint, (actuator, actuation))) in sim.joints.iter().zip(&sim.actuators).enumerate()
        {
            let force = inertial[i] + joint.bias_force();
            let control = match actuation {
                Actuation::Motor { gear } => force / gear,
                Actuation::Servo(gains) => {
                    (gains.gear * (gains.kp * state.reference[i] + gains.kv * state.speed[i])
                        + force / gains.gear)
                        / gains.gain
                }
            };
            actuator.set(control);
        }
    }
}

impl MotionControl for Controller {
    type Goal = Goal;
    type Error = SerialMotionError;

    /// Starts a motion after checking its whole path; its id.
    fn start(
        &self,
        goal: Self::Goal,
        speed: f64,
        acceleration: f64,
    ) -> Result<u64, SerialMotionError> {
        if !(speed > 0.0 && acceleration > 0.0 && speed.is_finite() && acceleration.is_finite()) {
            return Err(SerialMotionError::InvalidLimits {
                speed,
                acceleration,
            });
        }
        let mut state = self.state.borrow_mut();
        let from = state.reference.clone();
        let mut kinematics = self.kinematics.borrow_mut();
        let path = match goal {
            Goal::Joints(target) => {
                if !kinematics.within_limits(&target) {
                    return Err(SerialMotionError::InvalidTarget { target });
                }
                Path::Joints { from, to: target }
            }
            Goal::JointsFor(pose) => {
                let target = kinematics.solve(&pose, &from)?;
                Path::Joints { from, to: target }
            }
            Goal::Line(pose) => Path::Line {
                from: kinematics.forward(&from),
                to: pose,
                posture: from,
            },
        };
        let target = path.check(&mut kinematics, &state.reference)?;
        drop(kinematics);
        let profile = Profile::rest_to_rest(path.length(), speed, acceleration);
        let id = state
            .motions
            .start(path, profile, self.clock.time(), target);
        drop(state);
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
