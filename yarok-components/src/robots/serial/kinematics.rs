//! [`SerialKinematics`]: the forward and inverse kinematics of any serial chain of hinge or
//! slide joints, computed by MuJoCo on a scratch copy of the model's state, so that they are
//! the model's own.

use std::sync::Arc;

use nalgebra::{Isometry3, Matrix6, Vector3, Vector6};
use yarok_mjc::{BodyId, Data, JointId, Model, SiteId};

use crate::robots::ur::isometry_of;

/// How close (metres, radians) an inverse-kinematics solution puts the TCP to its target.
pub const SOLVED: f64 = 1e-7;

/// The most iterations an inverse-kinematics solve takes before the target counts as
/// unreachable.
const MAX_ITERATIONS: usize = 200;

/// Damping (metres) of the least-squares step: it keeps steps bounded near singularities.
const DAMPING: f64 = 1e-3;

/// The largest change of a joint (radians or metres) in one iteration.
const MAX_STEP: f64 = 0.2;

/// How many times a redundant arm's solution is moved along the null space towards the posture
/// asked for (and the task converged again) at most.
const POSTURE_ROUNDS: usize = 8;

/// A null-space move (radians) below which a redundant arm's posture counts as reached.
const POSTURE_SETTLED: f64 = 1e-6;

/// What the TCP of a [`SerialKinematics`] is: a site, or a body's frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TcpFrame {
    /// A site's frame.
    Site(SiteId),
    /// A body's frame (for files with no site at the hand).
    Body(BodyId),
}

/// Why no joints put the TCP at a pose.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SerialIkError {
    /// The pose is out of the arm's reach within its joint limits (or the solve met a
    /// singularity on the way): the TCP stays this far from it.
    #[error(
        "the pose is out of reach within the joint limits: the nearest the arm gets is {metres:.4} m and {radians:.4} rad from it"
    )]
    Unreachable {
        /// The distance left (metres).
        metres: f64,
        /// The rotation left (radians).
        radians: f64,
    },
    /// A pose or seed with a NaN or infinite number.
    #[error("a pose or joint angle is not finite")]
    NotFinite,
}

/// The forward and inverse kinematics of a serial arm in a model: its joints (base to tip), the
/// TCP frame, poses in the base frame (the frame of the body that carries the first joint,
/// taken as fixed in the world). Inverse kinematics is damped least squares on MuJoCo's
/// Jacobian of the TCP, within the joint limits; for an arm with more than six joints, the
/// redundancy is resolved towards the posture the solve starts from, so repeated solves along a
/// path do not drift.
///
/// It keeps a scratch state of its own: solving never touches the simulation.
///
/// # Examples
///
/// ```
/// use std::sync::Arc;
///
/// use yarok_components::robots::serial::{SerialKinematics, TcpFrame};
/// use yarok_mjc::Model;
///
/// let model = Arc::new(Model::from_xml_str(r#"<mujoco><compiler angle="radian"/>
///   <worldbody><body name="base">
///     <body name="upper"><joint name="shoulder" axis="0 1 0" range="-3 3"/>
///       <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.02"/>
///       <body name="lower" pos="0 0 -0.5"><joint name="elbow" axis="0 1 0" range="-3 3"/>
///         <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.02"/>
///         <site name="tip" pos="0 0 -0.5"/></body></body></body></worldbody></mujoco>"#)?);
/// let joints = [model.joint("shoulder")?, model.joint("elbow")?];
/// let mut arm = SerialKinematics::new(&model, &joints, TcpFrame::Site(model.site("tip")?))?;
/// let target = arm.forward(&[0.4, 0.8]);
/// let q = arm.solve(&target, &[0.3, 0.7])?;
/// assert!((q[0] - 0.4).abs() < 1e-6 && (q[1] - 0.8).abs() < 1e-6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct SerialKinematics {
    data: Data,
    joints: Vec<JointId>,
    /// Each joint's degree of freedom in the model's velocity vector.
    dofs: Vec<usize>,
    limits: Vec<[f64; 2]>,
    tcp: TcpFrame,
    /// The base frame in the world, and its inverse.
    base: Isometry3<f64>,
    to_base: Isometry3<f64>,
    translation: Vec<f64>,
    rotation: Vec<f64>,
    /// The TCP's Jacobian in the base frame, one column (linear, angular) per joint.
    columns: Vec<Vector6<f64>>,
}

impl std::fmt::Debug for SerialKinematics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SerialKinematics")
            .field("joints", &self.joints)
            .field("limits", &self.limits)
            .field("tcp", &self.tcp)
            .finish()
    }
}

impl SerialKinematics {
    /// The kinematics of the chain `joints` (hinge or slide joints, base to tip) with its TCP at
    /// `tcp`. A joint without limits may turn a whole turn either way.
    ///
    /// # Errors
    ///
    /// When a joint is not a hinge or slide joint, or the scratch state cannot be made.
    pub fn new(model: &Arc<Model>, joints: &[JointId], tcp: TcpFrame) -> Result<Self, String> {
        let mut data = Data::new(model).map_err(|e| e.to_string())?;
        let mut dofs = Vec::with_capacity(joints.len());
        let mut limits = Vec::with_capacity(joints.len());
        for &joint in joints {
            if data.qpos(joint).len() != 1 {
                let name = model.joint_name(joint).unwrap_or_default();
                return Err(format!(
                    "joint {name:?} is not a hinge or slide joint: a serial arm's joints turn or slide along one axis"
                ));
            }
            dofs.push(data.dof(joint));
            let full_turn = std::f64::consts::TAU;
            limits.push(model.joint_range(joint).unwrap_or([-full_turn, full_turn]));
        }
        let carrier = joints
            .first()
            .map(|&joint| model.body_parent(model.joint_body(joint)))
            .ok_or("a serial arm needs at least one joint")?;
        data.kinematics();
        let base = isometry_of(&data.body_pose(carrier));
        Ok(Self {
            data,
            joints: joints.to_vec(),
            dofs,
            limits,
            tcp,
            base,
            to_base: base.inverse(),
            translation: Vec::new(),
            rotation: Vec::new(),
            columns: vec![Vector6::zeros(); joints.len()],
        })
    }

    /// How many joints the chain has.
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// Each joint's limits, `[lower, upper]`.
    pub fn limits(&self) -> &[[f64; 2]] {
        &self.limits
    }

    /// The base frame in the world.
    pub fn base(&self) -> Isometry3<f64> {
        self.base
    }

    /// Whether every joint of `q` is finite and within its limits.
    pub fn within_limits(&self, q: &[f64]) -> bool {
        self.outside_limits(q).is_none()
    }

    /// Why `q` is not one finite number per joint within its limits (naming the joint and its
    /// limits), or `None` when it is.
    pub fn outside_limits(&self, q: &[f64]) -> Option<String> {
        if q.len() != self.limits.len() {
            return Some(format!(
                "{} numbers for {} joints",
                q.len(),
                self.limits.len()
            ));
        }
        let (i, (value, [lower, upper])) = q
            .iter()
            .zip(&self.limits)
            .enumerate()
            .find(|(_, (q, [lower, upper]))| !(q.is_finite() && (lower..=upper).contains(q)))?;
        let name = self
            .data
            .model()
            .joint_name(self.joints[i])
            .unwrap_or_else(|| format!("number {}", i + 1));
        Some(format!(
            "joint {name:?} at {value} is outside its limits [{lower}, {upper}]"
        ))
    }

    /// The TCP's pose in the base frame with the joints at `q`.
    ///
    /// # Panics
    ///
    /// When `q` does not hold one number per joint.
    pub fn forward(&mut self, q: &[f64]) -> Isometry3<f64> {
        assert_eq!(q.len(), self.joints.len(), "one angle per joint");
        for (&joint, &angle) in self.joints.iter().zip(q) {
            self.data.qpos_mut(joint)[0] = angle;
        }
        self.data.kinematics();
        self.to_base * self.tcp_in_world()
    }

    fn tcp_in_world(&self) -> Isometry3<f64> {
        match self.tcp {
            TcpFrame::Site(site) => isometry_of(&self.data.site_pose(site)),
            TcpFrame::Body(body) => isometry_of(&self.data.body_pose(body)),
        }
    }

    /// The joints that put the TCP at `target` (base frame), found from `near` (the current
    /// joints, usually) and so the solution nearest it: within the joint limits, the TCP within
    /// [`SOLVED`] of the target.
    ///
    /// # Errors
    ///
    /// [`SerialIkError::Unreachable`] when no joints within the limits reach the pose from
    /// `near`; [`SerialIkError::NotFinite`].
    ///
    /// # Panics
    ///
    /// When `near` does not hold one number per joint.
    pub fn solve(
        &mut self,
        target: &Isometry3<f64>,
        near: &[f64],
    ) -> Result<Vec<f64>, SerialIkError> {
        self.solve_towards(target, near, near)
    }

    /// As [`SerialKinematics::solve`], from `near`, with a redundant arm's extra joints drawn
    /// towards `posture` (the posture a line started from, so that a long line does not drift
    /// in the null space).
    ///
    /// # Errors
    ///
    /// As [`SerialKinematics::solve`].
    ///
    /// # Panics
    ///
    /// When `near` or `posture` does not hold one number per joint.
    pub fn solve_towards(
        &mut self,
        target: &Isometry3<f64>,
        near: &[f64],
        posture: &[f64],
    ) -> Result<Vec<f64>, SerialIkError> {
        assert_eq!(posture.len(), self.joints.len(), "one angle per joint");
        let finite = target.translation.vector.iter().all(|x| x.is_finite())
            && target.rotation.coords.iter().all(|x| x.is_finite())
            && near.iter().all(|x| x.is_finite());
        if !finite {
            return Err(SerialIkError::NotFinite);
        }
        let mut q: Vec<f64> = near
            .iter()
            .zip(&self.limits)
            .map(|(q, [lower, upper])| q.clamp(*lower, *upper))
            .collect();
        for _ in 0..POSTURE_ROUNDS {
            self.converge(target, &mut q)?;
            if self.joints.len() <= 6 || !self.towards_posture(&mut q, posture) {
                return Ok(q);
            }
        }
        self.converge(target, &mut q)?;
        Ok(q)
    }

    /// Damped least-squares steps from `q` until the TCP is within [`SOLVED`] of `target`;
    /// the Jacobian is left at the solution.
    fn converge(&mut self, target: &Isometry3<f64>, q: &mut [f64]) -> Result<(), SerialIkError> {
        let mut error = Vector6::zeros();
        for _ in 0..MAX_ITERATIONS {
            let at = self.forward(q);
            let linear = target.translation.vector - at.translation.vector;
            let angular = (target.rotation * at.rotation.inverse()).scaled_axis();
            error = Vector6::new(
                linear.x, linear.y, linear.z, angular.x, angular.y, angular.z,
            );
            self.jacobian();
            if linear.norm() < SOLVED && angular.norm() < SOLVED {
                return Ok(());
            }
            let Some(inverse) = self.damped_inverse(DAMPING) else {
                break;
            };
            let weights = inverse.solve(&error);
            let step: Vec<f64> = self.columns.iter().map(|c| c.dot(&weights)).collect();
            self.add(q, &step);
        }
        Err(SerialIkError::Unreachable {
            metres: error.fixed_rows::<3>(0).norm(),
            radians: error.fixed_rows::<3>(3).norm(),
        })
    }

    /// Moves a redundant arm's `q` within the Jacobian's null space (at `q`) to the posture
    /// nearest `posture`; whether it moved enough to need the task converged again.
    fn towards_posture(&mut self, q: &mut [f64], posture: &[f64]) -> bool {
        let Some(inverse) = self.damped_inverse(0.0) else {
            return false;
        };
        let pull: Vec<f64> = q.iter().zip(posture).map(|(q, p)| p - q).collect();
        let seen: Vector6<f64> = self.columns.iter().zip(&pull).map(|(c, p)| c * *p).sum();
        let back = inverse.solve(&seen);
        let step: Vec<f64> = pull
            .iter()
            .zip(&self.columns)
            .map(|(pull, column)| pull - column.dot(&back))
            .collect();
        self.add(q, &step) > POSTURE_SETTLED
    }

    /// The Cholesky factors of J Jᵀ + damping² I, `None` when singular.
    fn damped_inverse(&self, damping: f64) -> Option<nalgebra::Cholesky<f64, nalgebra::U6>> {
        let mut jjt = Matrix6::identity() * (damping * damping);
        for column in &self.columns {
            jjt += column * column.transpose();
        }
        jjt.cholesky()
    }

    /// `q` plus `step` (scaled down to [`MAX_STEP`] a joint), within the limits; the largest
    /// joint change `step` asked for.
    fn add(&self, q: &mut [f64], step: &[f64]) -> f64 {
        let largest = step.iter().fold(0.0_f64, |m, s| m.max(s.abs()));
        let scale = if largest > MAX_STEP {
            MAX_STEP / largest
        } else {
            1.0
        };
        for ((q, step), [lower, upper]) in q.iter_mut().zip(step).zip(&self.limits) {
            *q = (*q + step * scale).clamp(*lower, *upper);
        }
        largest
    }

    /// The TCP's Jacobian at the last [`SerialKinematics::forward`], into `columns`, in the
    /// base frame.
    fn jacobian(&mut self) {
        match self.tcp {
            TcpFrame::Site(site) => {
                self.data
                    .site_jacobian(site, &mut self.translation, &mut self.rotation);
            }
            TcpFrame::Body(body) => {
                self.data
                    .body_jacobian(body, &mut self.translation, &mut self.rotation);
            }
        }
        let nv = self.translation.len() / 3;
        let rotate = self.to_base.rotation;
        for (column, &dof) in self.columns.iter_mut().zip(&self.dofs) {
            let row =
                |rows: &[f64]| rotate * Vector3::new(rows[dof], rows[nv + dof], rows[2 * nv + dof]);
            let (linear, angular) = (row(&self.translation), row(&self.rotation));
            *column = Vector6::new(
                linear.x, linear.y, linear.z, angular.x, angular.y, angular.z,
            );
        }
    }
}
