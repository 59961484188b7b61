//! [`Arm`]: what a behaviour holds of a UR arm — its joints and TCP, and motions with the UR
//! controller's meaning (`movej`, `movel`, `stopj`), in platform time.

use std::cell::RefCell;
use std::future::{Future, IntoFuture};
use std::pin::Pin;
use std::rc::Rc;

use nalgebra::Isometry3;
use yarok_core::component::{Bind, BindError, Environment, Mock};
use yarok_core::time::{Clock, WaitError};
use yarok_mjc::{Actuator, Joint, Sim, SimBind};

use super::kinematics::{DhParameters, IkError, Joints, Kinematics, pose_from_vector};
use super::path::{Path, PathError};
use super::profile::Profile;

/// How close (radians, every joint) counts as arrived.
pub const ARRIVED_RAD: f64 = 1e-3;

/// How close (metres) counts as arrived for a pose ([`Arm::is_at_pose`]); its rotation within
/// [`ARRIVED_RAD`].
pub const ARRIVED_M: f64 = 1e-3;

/// Seconds after its profile ends that a motion may take to settle within [`ARRIVED_RAD`]
/// before it counts as failed (something blocks the arm).
pub const SETTLE_SECONDS: f64 = 0.5;

/// URScript's `movej` defaults: joint speed (rad/s) and acceleration (rad/s²).
pub const MOVE_J_DEFAULTS: (f64, f64) = (1.05, 1.4);

/// URScript's `movel` defaults: tool speed (m/s) and acceleration (m/s²).
pub const MOVE_L_DEFAULTS: (f64, f64) = (0.25, 1.2);

/// The joint and actuator names of a UR model, base to wrist 3.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArmNames {
    /// The hinge joints.
    pub joints: [&'static str; 6],
    /// The position servos driving them.
    pub actuators: [&'static str; 6],
}

impl ArmNames {
    /// The names in yarok's own [`Ur5`](super::Ur5) and [`Ur5e`](super::Ur5e) templates.
    pub const YAROK: Self = Self {
        joints: JOINTS,
        actuators: JOINTS,
    };

    /// The names in MuJoCo Menagerie's `universal_robots_ur5e/ur5e.xml`.
    pub const MENAGERIE: Self = Self {
        joints: [
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint",
        ],
        actuators: JOINTS,
    };
}

const JOINTS: [&str; 6] = [
    "shoulder_pan",
    "shoulder_lift",
    "elbow",
    "wrist_1",
    "wrist_2",
    "wrist_3",
];

/// How an [`Arm`] drives a model: its kinematics, names, where it starts, and the gains of its
/// position servos, from which the arm feeds the motion's speed and acceleration forward (a
/// servo that damps the joint's velocity lags a moving target by `kv / kp` times its speed;
/// accelerating the joint's inertia takes force too), so that it tracks without lag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmConfig {
    /// Kinematics with the joint limits and TCP the motions use.
    pub kinematics: Kinematics,
    /// Joint and actuator names in the model.
    pub names: ArmNames,
    /// Joint angles at the start of a run; `None` keeps the model's.
    pub start: Option<Joints>,
    /// `(kp, kv)` of each servo (force per radian of error, per rad/s of joint speed); a
    /// zero `kp` feeds nothing forward.
    pub gains: [(f64, f64); 6],
}

impl ArmConfig {
    /// An arm of `dh`, with yarok's names, starting where the model does, without feed-forward.
    pub fn new(dh: DhParameters) -> Self {
        Self {
            kinematics: Kinematics::new(dh),
            names: ArmNames::YAROK,
            start: None,
            gains: [(0.0, 0.0); 6],
        }
    }
}

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
    /// [`Arm::stop`] stopped it, or its future was dropped.
    #[error("the motion was stopped")]
    Stopped,
    /// A newer motion replaced it.
    #[error("a newer motion replaced this one")]
    Replaced,
    /// Its profile ended but the arm did not settle at the target (something blocks it).
    #[error(
        "the arm did not reach {target:?} within {SETTLE_SECONDS} s of the motion's end; it is at {at:?}"
    )]
    NotArrived {
        /// The target joints.
        target: Joints,
        /// Where the arm is.
        at: Joints,
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

/// A UR arm: joints, TCP pose, and motions in platform time. Cheap to clone.
#[derive(Clone)]
pub struct Arm {
    inner: Rc<Inner>,
}

struct Inner {
    kinematics: Kinematics,
    clock: Clock,
    drive: Drive,
    state: RefCell<State>,
}

/// What the motions move.
enum Drive {
    Sim(Box<Servos>),
    /// Follows the reference exactly.
    Mock,
}

/// The joints and position servos of an arm in `sim`.
struct Servos {
    joints: [Joint; 6],
    servos: [Actuator; 6],
    gains: [(f64, f64); 6],
}

struct State {
    /// The joints and speeds commanded for the next step.
    reference: Joints,
    speed: Joints,
    acceleration: Joints,
    motion: Option<Motion>,
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

impl std::fmt::Debug for Arm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Arm").field("q", &self.q()).finish()
    }
}

impl Arm {
    /// Binds an arm to a model in `sim` (yarok's templates, or any UR model given its names):
    /// its servos hold the initial pose, and the motions update them after every step.
    ///
    /// # Errors
    ///
    /// [`BindError`] when the model lacks a joint or actuator of `config.names`.
    pub fn bind_sim(bind: &mut Bind<Sim>, config: ArmConfig) -> Result<Self, BindError> {
        let names = config.names;
        let mut joints = Vec::with_capacity(6);
        let mut servos = Vec::with_capacity(6);
        for (joint, servo) in names.joints.iter().zip(names.actuators) {
            joints.push(bind.joint(joint)?);
            servos.push(bind.actuator(servo)?);
        }
        let joints: [Joint; 6] = joints.try_into().map_err(|_| bind.error("six joints"))?;
        let servos: [Actuator; 6] = servos.try_into().map_err(|_| bind.error("six servos"))?;
        if let Some(start) = config.start {
            for (joint, angle) in joints.iter().zip(start) {
                joint.set_position(angle);
            }
        }
        let start = joints.each_ref().map(Joint::position);
        let drive = Drive::Sim(Box::new(Servos {
            joints,
            servos,
            gains: config.gains,
        }));
        Ok(Self::with_drive(bind, config.kinematics, drive, start))
    }

    /// Binds an arm in `mock`: it follows its motions exactly, from `start`.
    pub fn bind_mock(bind: &mut Bind<Mock>, kinematics: Kinematics, start: Joints) -> Self {
        Self::with_drive(bind, kinematics, Drive::Mock, start)
    }

    fn with_drive<E: Environment>(
        bind: &mut Bind<E>,
        kinematics: Kinematics,
        drive: Drive,
        start: Joints,
    ) -> Self {
        let arm = Self {
            inner: Rc::new(Inner {
                kinematics,
                clock: bind.clock(),
                drive,
                state: RefCell::new(State {
                    reference: start,
                    speed: [0.0; 6],
                    acceleration: [0.0; 6],
                    motion: None,
                    next_id: 0,
                    ended: None,
                }),
            }),
        };
        arm.inner.command();
        let ticking = arm.clone();
        bind.on_tick(move || {
            ticking.inner.tick();
            Ok(())
        });
        arm
    }

    /// The kinematics the motions use (DH parameters, joint limits, TCP).
    pub fn kinematics(&self) -> &Kinematics {
        &self.inner.kinematics
    }

    /// Joint angles (radians).
    pub fn q(&self) -> Joints {
        match &self.inner.drive {
            Drive::Sim(sim) => sim.joints.each_ref().map(Joint::position),
            Drive::Mock => self.inner.state.borrow().reference,
        }
    }

    /// Joint speeds (rad/s).
    pub fn qd(&self) -> Joints {
        match &self.inner.drive {
            Drive::Sim(sim) => sim.joints.each_ref().map(Joint::velocity),
            Drive::Mock => self.inner.state.borrow().speed,
        }
    }

    /// The TCP's pose in the base frame.
    pub fn tcp_pose(&self) -> Isometry3<f64> {
        self.inner.kinematics.forward(&self.q())
    }

    /// Whether every joint is within [`ARRIVED_RAD`] of `target`.
    pub fn is_at(&self, target: &Joints) -> bool {
        within(&self.q(), target)
    }

    /// Whether the TCP is within [`ARRIVED_M`] (and [`ARRIVED_RAD`]) of `pose`.
    pub fn is_at_pose(&self, pose: &Isometry3<f64>) -> bool {
        let at = self.tcp_pose();
        (at.translation.vector - pose.translation.vector).norm() < ARRIVED_M
            && at.rotation.angle_to(&pose.rotation) < ARRIVED_RAD
    }

    /// Whether a motion is under way.
    pub fn is_moving(&self) -> bool {
        self.inner.state.borrow().motion.is_some()
    }

    /// A joint motion to `target` (URScript `movej`): every joint starts and stops together,
    /// the one moving furthest at the speed and acceleration given ([`MOVE_J_DEFAULTS`]).
    /// `.await` it (it resolves on arrival; dropping it stops the arm), or [`Move::start`] it.
    pub fn move_j(&self, target: Joints) -> Move<'_> {
        self.motion(Goal::Joints(target), MOVE_J_DEFAULTS)
    }

    /// A joint motion (as [`Arm::move_j`]) to the joints nearest the current ones that put the
    /// TCP at `pose` (URScript `movej` given a pose): the TCP's path is not a line, which lets
    /// it go round the base where a line would pass too close to it.
    pub fn move_j_pose(&self, pose: Isometry3<f64>) -> Move<'_> {
        self.motion(Goal::JointsFor(pose), MOVE_J_DEFAULTS)
    }

    fn motion(&self, goal: Goal, (speed, acceleration): (f64, f64)) -> Move<'_> {
        Move {
            arm: self,
            goal,
            speed,
            acceleration,
        }
    }

    /// A straight-line motion of the TCP to `pose` in the base frame (URScript `movel`): the
    /// TCP moves along the line (turning on the way) at the speed and acceleration given
    /// ([`MOVE_L_DEFAULTS`]). `.await` it, or [`Move::start`] it.
    pub fn move_l(&self, pose: Isometry3<f64>) -> Move<'_> {
        self.motion(Goal::Line(pose), MOVE_L_DEFAULTS)
    }

    /// [`Arm::move_l`] to a UR pose vector `[x, y, z, rx, ry, rz]`.
    pub fn move_l_vector(&self, pose: [f64; 6]) -> Move<'_> {
        self.move_l(pose_from_vector(pose))
    }

    /// Stops the motion under way: it decelerates along its path (a line stays a line) at its
    /// own acceleration; its awaiting future ends with [`MotionError::Stopped`].
    pub fn stop(&self) {
        self.inner.stop(None);
    }
}

impl Inner {
    /// After a step: the reference for the next one, and whether the motion has ended.
    fn tick(&self) {
        let now = self.clock.time() + self.clock.timestep();
        self.advance(now);
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
        let outcome = match motion.reference(t, dt, &self.kinematics, &state.reference) {
            Err(error) => Some(Err(error.into())),
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
        if motion.stopping {
            Some(Err(MotionError::Stopped))
        } else if within(&at, &motion.target) {
            Some(Ok(()))
        } else if now - (motion.started + motion.profile.duration()) > SETTLE_SECONDS {
            Some(Err(MotionError::NotArrived {
                target: motion.target,
                at,
            }))
        } else {
            None
        }
    }

    fn measured(&self, state: &State) -> Joints {
        match &self.drive {
            Drive::Sim(sim) => sim.joints.each_ref().map(Joint::position),
            Drive::Mock => state.reference,
        }
    }

    /// Sets the servos to the reference (plus velocity feed-forward).
    fn command(&self) {
        if let Drive::Sim(sim) = &self.drive {
            let state = self.state.borrow();
            for (i, (kp, kv)) in sim.gains.iter().enumerate() {
                let mut target = state.reference[i];
                if *kp > 0.0 {
                    let inertia = sim.joints[i].inertia();
                    target += (kv * state.speed[i] + inertia * state.acceleration[i]) / kp;
                }
                sim.servos[i].set(target);
            }
        }
    }

    /// Starts a motion to `to`, after checking the whole path; its id.
    fn start(&self, goal: Goal, speed: f64, acceleration: f64) -> Result<u64, MotionError> {
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
    fn stop(&self, id: Option<u64>) {
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
        motion.profile = Profile::stopping(along, speed, deceleration);
        motion.started = now;
        motion.stopping = true;
    }

    /// How motion `id` is: `None` while under way.
    fn outcome(&self, id: u64) -> Option<Result<(), MotionError>> {
        let state = self.state.borrow();
        match (&state.motion, &state.ended) {
            (Some(motion), _) if motion.id == id => None,
            (_, Some((ended, outcome))) if *ended == id => Some(outcome.clone()),
            _ => Some(Err(MotionError::Replaced)),
        }
    }
}

fn within(q: &Joints, target: &Joints) -> bool {
    q.iter()
        .zip(target)
        .all(|(a, b)| (a - b).abs() < ARRIVED_RAD)
}

/// Where a motion goes, and how.
#[derive(Debug, Clone, Copy)]
enum Goal {
    Joints(Joints),
    /// In joint space, to the joints that put the TCP at the pose.
    JointsFor(Isometry3<f64>),
    /// The TCP along a straight line.
    Line(Isometry3<f64>),
}

/// A motion about to start: set its speed and acceleration, then `.await` it (it resolves on
/// arrival) or [`Move::start`] it and wait yourself (`pl.wait(|| arm.is_at(&q))`).
///
/// # Cancel safety
///
/// Dropping the awaited future before arrival stops the arm (as [`Arm::stop`]).
#[must_use = "a motion does nothing until awaited or started"]
#[derive(Debug)]
pub struct Move<'a> {
    arm: &'a Arm,
    goal: Goal,
    speed: f64,
    acceleration: f64,
}

impl Move<'_> {
    /// The speed: of the leading joint (rad/s) for `move_j`, of the TCP (m/s) for `move_l`.
    pub fn speed(mut self, speed: f64) -> Self {
        self.speed = speed;
        self
    }

    /// The acceleration: rad/s² for `move_j`, m/s² for `move_l`.
    pub fn acceleration(mut self, acceleration: f64) -> Self {
        self.acceleration = acceleration;
        self
    }

    /// Starts the motion and returns at once; it goes on until it arrives, is stopped or a
    /// newer motion replaces it.
    ///
    /// # Errors
    ///
    /// [`MotionError`] when the target or a point on the way cannot be reached, or the limits
    /// are not positive numbers: nothing moves then.
    pub fn start(self) -> Result<(), MotionError> {
        self.arm
            .inner
            .start(self.goal, self.speed, self.acceleration)
            .map(drop)
    }
}

impl<'a> IntoFuture for Move<'a> {
    type Output = Result<(), MotionError>;
    type IntoFuture = Pin<Box<dyn Future<Output = Self::Output> + 'a>>;

    fn into_future(self) -> Self::IntoFuture {
        Box::pin(async move {
            let inner = &self.arm.inner;
            let id = inner.start(self.goal, self.speed, self.acceleration)?;
            // Dropped with the future: stops the motion if it is still under way.
            let _stop_if_dropped = StopIfDropped { inner, id };
            let mut outcome = None;
            inner
                .clock
                .wait(|| {
                    outcome = inner.outcome(id);
                    outcome.is_some()
                })
                .await?;
            outcome.unwrap_or(Err(MotionError::Replaced))
        })
    }
}

/// Stops motion `id` when its future is dropped before it ends.
struct StopIfDropped<'a> {
    inner: &'a Inner,
    id: u64,
}

impl Drop for StopIfDropped<'_> {
    fn drop(&mut self) {
        self.inner.stop(Some(self.id));
    }
}
