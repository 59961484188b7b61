//! [`Arm`]: what a behaviour holds of a UR arm — its joints and TCP, and motions with the UR
//! controller's meaning (`movej`, `movel`, `stopj`), in platform time.

use std::rc::Rc;

use nalgebra::Isometry3;
use yarok_core::component::{Bind, BindError, Environment, Mock};
use yarok_mjc::Sim;

use super::Move;
use super::config::ArmConfig;
use super::controller::{Controller, Goal};
use super::drive::ArmDrive;
use super::exposed;
use super::kinematics::{Joints, Kinematics, pose_from_vector};
use super::mock::FollowingJoints;
use super::payload::Payload;
use super::sim::Servos;
use super::streaming::ServoLimits;
use crate::robots::motion::MotionControl;
use crate::robots::motions::{ARRIVED_M, ARRIVED_RAD, MOVE_J_DEFAULTS, MOVE_L_DEFAULTS, within};

/// A UR arm: joints, TCP pose, and motions in platform time. Cheap to clone.
#[derive(Clone)]
pub struct Arm {
    controller: Rc<Controller>,
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
        let servos = Servos::bind(bind, &config.names)?;
        let start = servos.start_at(config.start);
        Ok(Self::with_drive(
            bind,
            config.kinematics,
            Rc::new(servos),
            start,
        ))
    }

    /// Binds a real arm through its controller (interface settings `host`, `rtde_hz`,
    /// `reply_seconds`, `connect_seconds`): refused when the controller's arm has other
    /// kinematics than `kinematics`' (a UR5 configured on a UR5e); motions go to the controller
    /// as URScript with the same meaning; the joints come from RTDE; the arm is stopped at
    /// shutdown.
    ///
    /// # Errors
    ///
    /// [`BindError`] naming the controller when it cannot be reached or its arm differs.
    pub async fn bind_real(
        bind: &mut Bind<yarok_hw::Real>,
        kinematics: Kinematics,
    ) -> Result<Self, BindError> {
        let (link, start) = super::real::connect(bind, &kinematics).await?;
        Ok(Self::with_drive(bind, kinematics, link, start))
    }

    /// Binds an arm in `mock`: it follows its motions exactly, from `start`.
    pub fn bind_mock(bind: &mut Bind<Mock>, kinematics: Kinematics, start: Joints) -> Self {
        Self::with_drive(bind, kinematics, Rc::new(FollowingJoints), start)
    }

    /// An arm over `drive` (a user's own environment: a replay, another simulator), its
    /// motions planned with `kinematics` from `start`: the controller commands the drive after
    /// every step, and from `start` again when an episode begins if the drive
    /// [is put back](ArmDrive::is_put_back_at_restart). It publishes its `state` (`q`, `qd`,
    /// `tcp`) and takes `command`s (`{"move_j": [q…], "speed": …, "acceleration": …}`,
    /// `{"move_l": [x, y, z, rx, ry, rz], …}`, `{"stop": true}`) for any plugin.
    pub fn with_drive<E: Environment>(
        bind: &mut Bind<E>,
        kinematics: Kinematics,
        drive: Rc<dyn ArmDrive>,
        start: Joints,
    ) -> Self {
        let put_back = drive.is_put_back_at_restart();
        let controller = Rc::new(Controller::new(bind.clock(), kinematics, drive, start));
        controller.command();
        let restarting = Rc::clone(&controller);
        if put_back {
            bind.on_restart(move || restarting.restart(start));
        } else {
            // Hardware stays where it is: the next episode's first target is approached from
            // where the arm is measured then.
            bind.on_restart(move || restarting.end_stream());
        }
        let ticking = Rc::clone(&controller);
        bind.on_tick(move || {
            ticking.tick();
            Ok(())
        });
        let arm = Self { controller };
        exposed::expose(bind, &arm);
        arm
    }

    /// The kinematics the motions use (DH parameters, joint limits, TCP).
    pub fn kinematics(&self) -> &Kinematics {
        self.controller.kinematics()
    }

    /// Joint angles (radians).
    pub fn q(&self) -> Joints {
        self.controller.q()
    }

    /// Joint speeds (rad/s).
    pub fn qd(&self) -> Joints {
        self.controller.qd()
    }

    /// The TCP's pose in the base frame.
    pub fn tcp_pose(&self) -> Isometry3<f64> {
        self.controller.kinematics().forward(&self.q())
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

    /// Sets what the arm carries at its flange (URScript `set_payload`): `mass` kilograms centred
    /// at `centre` (metres, flange frame). A real arm's controller is told; in `sim` the servos
    /// hold its weight as they hold the arm's own, so a heavy tool or grasped object does not
    /// make the arm sag.
    ///
    /// # Errors
    ///
    /// When the mass is negative or a number is not finite.
    pub fn set_payload(&self, mass: f64, centre: [f64; 3]) -> Result<(), String> {
        self.controller.set_payload(Payload::new(mass, centre)?);
        Ok(())
    }

    /// Whether a motion is under way.
    pub fn is_moving(&self) -> bool {
        self.controller.is_moving()
    }

    /// A joint motion to `target` (URScript `movej`): every joint starts and stops together,
    /// the one moving furthest at the speed and acceleration given ([`MOVE_J_DEFAULTS`]).
    /// `.await` it (it resolves on arrival; dropping it stops the arm), or [`Motion::start`](crate::robots::Motion::start) it.
    pub fn move_j(&self, target: Joints) -> Move<'_> {
        self.motion(Goal::Joints(target), MOVE_J_DEFAULTS)
    }

    /// A joint motion (as [`Arm::move_j`]) to the joints nearest the current ones that put the
    /// TCP at `pose` (URScript `movej` given a pose): the TCP's path is not a line, which lets
    /// it go round the base where a line would pass too close to it.
    pub fn move_j_pose(&self, pose: Isometry3<f64>) -> Move<'_> {
        self.motion(Goal::JointsFor(pose), MOVE_J_DEFAULTS)
    }

    fn motion(&self, goal: Goal, defaults: (f64, f64)) -> Move<'_> {
        Move::new(&*self.controller, goal, defaults)
    }

    /// A straight-line motion of the TCP to `pose` in the base frame (URScript `movel`): the
    /// TCP moves along the line (turning on the way) at the speed and acceleration given
    /// ([`MOVE_L_DEFAULTS`]). `.await` it, or [`Motion::start`](crate::robots::Motion::start) it.
    pub fn move_l(&self, pose: Isometry3<f64>) -> Move<'_> {
        self.motion(Goal::Line(pose), MOVE_L_DEFAULTS)
    }

    /// [`Arm::move_l`] to a UR pose vector `[x, y, z, rx, ry, rz]`.
    pub fn move_l_vector(&self, pose: [f64; 6]) -> Move<'_> {
        self.move_l(pose_from_vector(pose))
    }

    /// Unlocks a protective stop (a real arm, through its controller's dashboard; the
    /// controller refuses within 5 s of the stop). Nothing to do in `sim` and `mock`.
    ///
    /// # Errors
    ///
    /// The controller's refusal, or why it could not be asked.
    pub async fn unlock_protective_stop(&self) -> Result<(), String> {
        self.controller.unlock_protective_stop().await
    }

    /// Streams a joint target, as URScript's `servoj` does: a motion under way ends as
    /// stopped, and from the next step the arm approaches `target`, due `seconds` later (a
    /// policy's control period), within its [servo limits](Arm::servo_limits): a target
    /// farther than the period allows is approached at the limits and reached at rest; a
    /// target not followed by another is held. A stream begins where the arm is measured.
    /// What a policy's action sets. [`Arm::stop`] brings it to rest within the limits.
    ///
    /// A real arm is ordered each target's `servoj` toward where the approach will be when the
    /// target is due, so that it is never asked beyond the limits either; only the latest is
    /// sent when the link falls behind.
    ///
    /// # Errors
    ///
    /// [`MotionError::InvalidTarget`](super::MotionError::InvalidTarget) when a joint is
    /// beyond its limits or not a number; the reason the arm cannot move
    /// ([`MotionError::SafetyStop`](super::MotionError::SafetyStop),
    /// [`MotionError::NotRunning`](super::MotionError::NotRunning)) while it cannot: the stream
    /// ends; after it, [`MotionError::StreamStopped`](super::MotionError::StreamStopped) until
    /// [`Arm::rearm`] (or an episode's begin), even once the stop has cleared.
    pub fn servo_j(&self, target: Joints, seconds: f64) -> Result<(), super::MotionError> {
        self.controller.servo(target, seconds)
    }

    /// The joint angles commanded for the next step: where a motion is due, or where a
    /// streamed target's approach is.
    pub fn commanded(&self) -> Joints {
        self.controller.setpoint()
    }

    /// Where the joints are commanded to be `seconds` from now: the streamed target being
    /// approached ([`Arm::servo_j`]), or where the motion under way is due then, or where the
    /// arm is held. What a policy would stream now to go on as the arm goes: a dataset's
    /// `action` for a frame, `seconds` the frame period.
    pub fn target_in(&self, seconds: f64) -> Joints {
        self.controller.target_in(seconds)
    }

    /// Re-arms a stream of targets that a stop ended ([`MotionError::StreamStopped`](super::MotionError::StreamStopped)):
    /// the next target begins a stream from where the arm is measured then. Beginning an
    /// episode does the same.
    pub fn rearm(&self) {
        self.controller.end_stream();
    }

    /// The per-joint speed and acceleration limits streamed targets are approached within
    /// (by default the arm's datasheet speed, 180°/s, and 360°/s²).
    pub fn servo_limits(&self) -> ServoLimits {
        self.controller.servo_limits()
    }

    /// Sets the limits streamed targets are approached within, from the next step.
    pub fn set_servo_limits(&self, limits: ServoLimits) {
        self.controller.set_servo_limits(limits);
    }

    /// Stops the motion under way: it decelerates along its path (a line stays a line) at its
    /// own acceleration; its awaiting future ends with [`MotionError::Stopped`](super::MotionError::Stopped).
    /// A stream of targets ([`Arm::servo_j`]) comes to rest within the servo limits.
    pub fn stop(&self) {
        self.controller.stop(None);
    }
}
