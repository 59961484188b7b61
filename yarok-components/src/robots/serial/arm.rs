//! [`SerialArm`]: what a behaviour holds of any serial arm — joints, TCP, and motions with the
//! UR arms' meaning (`move_j`, `move_l`, `stop`) in platform time.

use std::rc::Rc;

use nalgebra::Isometry3;
use yarok_core::component::{Bind, BindError};
use yarok_mjc::{Sim, SimBind};

use super::actuated_joints::actuated_joints;
use super::controller::{Controller, Goal};
use super::dynamics::{Dynamics, JointDynamics};
use super::error::SerialMotionError;
use super::kinematics::{SerialKinematics, TcpFrame};
use super::names::SerialNames;
use crate::robots::Motion;
use crate::robots::motion::MotionControl;
use crate::robots::motions::{ARRIVED_M, ARRIVED_RAD, MOVE_J_DEFAULTS, MOVE_L_DEFAULTS, within};

/// How stiffly (rad/s, the natural frequency of the tracking error) motor-driven joints follow
/// their reference unless told otherwise.
pub const DEFAULT_STIFFNESS: f64 = 40.0;

/// Any serial arm in `sim`, given its joints, actuators and TCP ([`SerialNames`]): the same
/// motions as the UR arms' [`Arm`](crate::robots::ur::Arm) — trapezoidal profiles in platform
/// time with URScript's speed and acceleration defaults, the whole path checked before
/// anything moves, arrival within [`ARRIVED_RAD`], a stop on drop — with inverse kinematics by
/// damped least squares on MuJoCo's Jacobian ([`SerialKinematics`]). Gravity and the rest of
/// MuJoCo's bias forces are compensated as a real arm's controller does, whether or not the
/// file declares `gravcomp`; torque motors (`<motor>`, as robosuite's arms have) track with a
/// critically damped stiffness, position servos with their own gains. Poses are in the base
/// frame (of the body that carries the first joint). Cheap to clone.
#[derive(Clone)]
pub struct SerialArm {
    controller: Rc<Controller>,
    start: Rc<Vec<f64>>,
}

impl std::fmt::Debug for SerialArm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SerialArm").field("q", &self.q()).finish()
    }
}

impl SerialArm {
    /// Binds the arm `names` describes in the component's model, starting at `start` (the
    /// model's initial joints when `None`), motors tracking with `stiffness` (rad/s; see
    /// [`DEFAULT_STIFFNESS`]).
    ///
    /// # Errors
    ///
    /// [`BindError`] when a name is missing (listing the names the file has), the joint and
    /// actuator lists differ in length, an actuator is neither a motor nor a position servo on
    /// a joint, or `start` is outside the joint limits.
    pub fn bind_sim(
        bind: &mut Bind<Sim>,
        names: &SerialNames,
        start: Option<&[f64]>,
        stiffness: f64,
    ) -> Result<Self, BindError> {
        if !(stiffness > 0.0 && stiffness.is_finite()) {
            return Err(bind.error(format!("stiffness {stiffness} must be a positive number")));
        }
        let drives = actuated_joints(bind, names)?;
        let model = std::sync::Arc::clone(bind.backend().model());
        let tcp = tcp_frame(bind, names.tcp)?;
        let last_body = model.joint_body(drives[drives.len() - 1].joint.id());
        let tcp_body = match tcp {
            TcpFrame::Site(site) => model.site_body(site),
            TcpFrame::Body(body) => body,
        };
        if !model.carries(last_body, tcp_body) {
            return Err(bind.error(format!(
                "the TCP {:?} is not carried by the arm's last joint {:?}: it must be on the \
                 body of the last joint or a body below it",
                names.tcp,
                drives[drives.len() - 1].name
            )));
        }
        let ids: Vec<_> = drives.iter().map(|drive| drive.joint.id()).collect();
        let kinematics = SerialKinematics::new(&model, &ids, tcp).map_err(|e| bind.error(e))?;
        if let Some(start) = start {
            if let Some(reason) = kinematics.outside_limits(start) {
                return Err(bind.error(format!("start {start:?}: {reason}")));
            }
            for (drive, angle) in drives.iter().zip(start) {
                drive.joint.set_position(*angle);
            }
        }
        let start: Vec<f64> = drives.iter().map(|drive| drive.joint.position()).collect();
        let dynamics = Dynamics::new(
            &model,
            drives
                .iter()
                .map(|drive| JointDynamics {
                    id: drive.joint.id(),
                    losses: drive.losses,
                    force_range: drive.force_range,
                })
                .collect(),
        )
        .map_err(|e| bind.error(e))?;
        let controller = Rc::new(Controller::new(
            bind.clock(),
            kinematics,
            dynamics,
            drives,
            stiffness,
            start.clone(),
        ));
        controller.command();
        let restarting = Rc::clone(&controller);
        let start = Rc::new(start);
        let start_again = Rc::clone(&start);
        bind.on_restart(move || restarting.restart(&start_again));
        let ticking = Rc::clone(&controller);
        bind.on_tick(move || {
            ticking.tick();
            Ok(())
        });
        Ok(Self { controller, start })
    }

    /// The joints at the start of the run.
    pub fn start(&self) -> &[f64] {
        &self.start
    }

    /// Joint angles (radians; metres for slide joints).
    pub fn q(&self) -> Vec<f64> {
        self.controller.q()
    }

    /// Joint speeds.
    pub fn qd(&self) -> Vec<f64> {
        self.controller.qd()
    }

    /// Each joint's limits, `[lower, upper]`.
    pub fn limits(&self) -> Vec<[f64; 2]> {
        self.controller.kinematics().limits().to_vec()
    }

    /// The TCP's pose in the base frame, as MuJoCo puts it at the current joints.
    pub fn tcp_pose(&self) -> Isometry3<f64> {
        let q = self.q();
        self.controller.kinematics().forward(&q)
    }

    /// The joints nearest `near` that put the TCP at `pose` (base frame), as the motions find
    /// them (see [`SerialKinematics::solve`]).
    ///
    /// # Errors
    ///
    /// As [`SerialKinematics::solve`].
    pub fn solve(
        &self,
        pose: &Isometry3<f64>,
        near: &[f64],
    ) -> Result<Vec<f64>, super::SerialIkError> {
        self.controller.kinematics().solve(pose, near)
    }

    /// Whether every joint is within [`ARRIVED_RAD`] of `target`.
    pub fn is_at(&self, target: &[f64]) -> bool {
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
        self.controller.is_moving()
    }

    /// A joint motion to `target` (URScript `movej`'s meaning): every joint starts and stops
    /// together, the one moving furthest at the speed and acceleration given
    /// ([`MOVE_J_DEFAULTS`]). `.await` it, or [`Motion::start`] it.
    pub fn move_j(&self, target: Vec<f64>) -> SerialMove<'_> {
        self.motion(Goal::Joints(target), MOVE_J_DEFAULTS)
    }

    /// A joint motion to the joints nearest the current ones that put the TCP at `pose`.
    pub fn move_j_pose(&self, pose: Isometry3<f64>) -> SerialMove<'_> {
        self.motion(Goal::JointsFor(pose), MOVE_J_DEFAULTS)
    }

    /// A straight-line motion of the TCP to `pose` (URScript `movel`'s meaning), at the speed
    /// and acceleration given ([`MOVE_L_DEFAULTS`]).
    pub fn move_l(&self, pose: Isometry3<f64>) -> SerialMove<'_> {
        self.motion(Goal::Line(pose), MOVE_L_DEFAULTS)
    }

    fn motion(&self, goal: Goal, defaults: (f64, f64)) -> SerialMove<'_> {
        Motion::new(&*self.controller, goal, defaults)
    }

    /// Stops the motion under way: it decelerates along its path at its own acceleration; its
    /// awaiting future ends with [`SerialMotionError::Stopped`].
    pub fn stop(&self) {
        self.controller.stop(None);
    }
}

/// A serial arm's motion about to start ([`SerialArm::move_j`], [`SerialArm::move_l`]):
/// `.await` it, or [`Motion::start`] it.
pub type SerialMove<'a> = Motion<'a, SerialMotionError>;

/// The TCP `name` names: a site, or else a body; an error with the sites and bodies the
/// template has when it is neither.
fn tcp_frame(bind: &mut Bind<Sim>, name: &str) -> Result<TcpFrame, BindError> {
    let site_error = match bind.site(name) {
        Ok(site) => return Ok(TcpFrame::Site(site.id())),
        Err(error) => error,
    };
    let body_error = match bind.body(name) {
        Ok(body) => return Ok(TcpFrame::Body(body.id())),
        Err(error) => error,
    };
    let hint = |error: BindError| match error {
        BindError::NoName { hint, .. } => hint.trim_start_matches("; ").to_owned(),
        other => other.to_string(),
    };
    Err(bind.error(format!(
        "the TCP {name:?} is neither a site nor a body of its template (sites: {}; bodies: {})",
        hint(site_error),
        hint(body_error)
    )))
}
