//! [`Data`]: the simulation state of a [`Model`], and stepping it.

use std::fmt;
use std::ptr::NonNull;
use std::sync::Arc;

use crate::error::ModelError;
use crate::model::{
    ActuatorId, BodyId, CameraId, GeomId, JointId, KeyframeId, Model, SensorId, SiteId, to_usize,
};
use crate::pose::Pose;
use crate::sys;

/// MuJoCo's functions that write a frame's translation and rotation Jacobians
/// (`mj_jacSite`, `mj_jacBody`).
type FrameJacobian = unsafe extern "C" fn(
    *const sys::mjModel,
    *const sys::mjData,
    *mut f64,
    *mut f64,
    std::os::raw::c_int,
);

/// What [`Data::save_state`] saves: MuJoCo's integration state without the time.
const SAVED_STATE: sys::mjtState = sys::mjSTATE_INTEGRATION & !sys::mjSTATE_TIME;

/// A simulation state [`Data::save_state`] saved, for [`Data::restore_state`].
#[derive(Clone)]
pub struct SavedState {
    model: Arc<Model>,
    values: Vec<f64>,
}

impl fmt::Debug for SavedState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SavedState")
            .field("numbers", &self.values.len())
            .finish()
    }
}

/// The state of one simulation of a [`Model`] (`mjData`): time, positions, velocities,
/// controls, sensor readings and everything computed from them.
///
/// `Data` keeps its model alive. It may move between threads but is used from one at a time.
///
/// # Examples
///
/// ```
/// use std::sync::Arc;
/// use yarok_mjc::{Data, Model};
///
/// let model = Arc::new(Model::from_xml_str(
///     r#"<mujoco><worldbody><body name="ball" pos="0 0 1"><freejoint name="free"/>
///        <geom size="0.1"/></body></worldbody></mujoco>"#,
/// )?);
/// let mut data = Data::new(&model)?;
/// let free = model.joint("free")?;
/// for _ in 0..100 {
///     data.step();
/// }
/// assert!(data.qpos(free)[2] < 1.0, "the ball falls");
/// assert!((data.time() - 100.0 * model.timestep()).abs() < 1e-9);
/// # Ok::<(), yarok_mjc::ModelError>(())
/// ```
pub struct Data {
    raw: NonNull<sys::mjData>,
    model: Arc<Model>,
}

// SAFETY: a Data owns its mjData (plain memory with no thread affinity) and an Arc of a Send +
// Sync model; moving both to another thread is sound. It is not Sync: stepping needs `&mut`.
unsafe impl Send for Data {}

impl Data {
    /// Allocates the state of `model`, at its initial configuration (`qpos0`).
    ///
    /// # Errors
    ///
    /// [`ModelError::Allocation`] when MuJoCo cannot allocate the state.
    pub fn new(model: &Arc<Model>) -> Result<Self, ModelError> {
        // SAFETY: the model pointer is valid; mj_makeData returns null on allocation failure.
        let raw = unsafe { model.mj().mj_makeData(model.raw()) };
        let raw = NonNull::new(raw).ok_or(ModelError::Allocation { what: "mjData" })?;
        Ok(Self {
            raw,
            model: Arc::clone(model),
        })
    }

    /// The model this state belongs to.
    pub fn model(&self) -> &Arc<Model> {
        &self.model
    }

    /// Advances the simulation by one timestep.
    ///
    /// MuJoCo logs the first of each kind of warning (a NaN or infinite control, which it
    /// zeroes; an unstable state, which it resets) as a `tracing` warning with target `mujoco`.
    pub fn step(&mut self) {
        // SAFETY: model and data are valid and belong together.
        unsafe { self.model.mj().mj_step(self.model.raw(), self.raw.as_ptr()) }
    }

    /// Computes everything derived from the current state (positions, sensors, …) without
    /// advancing time.
    pub fn forward(&mut self) {
        // SAFETY: model and data are valid and belong together.
        unsafe {
            self.model
                .mj()
                .mj_forward(self.model.raw(), self.raw.as_ptr())
        }
    }

    /// Computes where every body, site and joint axis is from the positions alone (MuJoCo's
    /// `mj_kinematics` and `mj_comPos`): enough for poses and Jacobians, and much cheaper than
    /// [`Data::forward`] — for kinematics on a scratch `Data`.
    pub fn kinematics(&mut self) {
        // SAFETY: model and data are valid and belong together.
        unsafe {
            let (mj, m) = (self.model.mj(), self.model.raw());
            mj.mj_kinematics(m, self.raw.as_ptr());
            mj.mj_comPos(m, self.raw.as_ptr());
        }
    }

    /// Resets the state to the model's initial configuration and time 0.
    pub fn reset(&mut self) {
        // SAFETY: model and data are valid and belong together.
        unsafe {
            self.model
                .mj()
                .mj_resetData(self.model.raw(), self.raw.as_ptr())
        }
    }

    /// Resets the state to a keyframe: its time, positions, velocities, controls and
    /// activations.
    ///
    /// # Panics
    ///
    /// When `keyframe` was resolved in a different model.
    #[track_caller]
    pub fn reset_to_keyframe(&mut self, keyframe: KeyframeId) {
        let index = self.model.index_of(keyframe) as i32;
        // SAFETY: model and data belong together and `index` < nkey for an id of this model.
        unsafe {
            self.model
                .mj()
                .mj_resetDataKeyframe(self.model.raw(), self.raw.as_ptr(), index)
        }
    }

    /// Saves everything that determines how the simulation goes on from here — positions,
    /// velocities, activations, the solver's warm start, controls, applied forces, mocap poses,
    /// active equalities, plugin and user data (MuJoCo's `mjSTATE_INTEGRATION`) — but not the
    /// time; [`Data::restore_state`] brings it back.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::Arc;
    /// use yarok_mjc::{Data, Model};
    ///
    /// let model = Arc::new(Model::from_xml_str(
    ///     r#"<mujoco><worldbody><body name="ball" pos="0 0 1"><freejoint name="free"/>
    ///        <geom size="0.1"/></body></worldbody></mujoco>"#,
    /// )?);
    /// let mut data = Data::new(&model)?;
    /// let start = data.save_state();
    /// for _ in 0..100 {
    ///     data.step();
    /// }
    /// data.restore_state(&start);
    /// assert_eq!(data.qpos(model.joint("free")?)[2], 1.0, "back where it started");
    /// assert!(data.time() > 0.0, "time goes on");
    /// # Ok::<(), yarok_mjc::ModelError>(())
    /// ```
    pub fn save_state(&self) -> SavedState {
        // SAFETY: the model is valid; the signature is one of MuJoCo's state signatures.
        let size = unsafe {
            self.model
                .mj()
                .mj_stateSize(self.model.raw(), SAVED_STATE as i32)
        };
        let mut values = vec![0.0; usize::try_from(size).unwrap_or(0)];
        // SAFETY: model and data belong together; `values` holds mj_stateSize(SAVED_STATE)
        // numbers, what mj_getState writes for that signature.
        unsafe {
            self.model.mj().mj_getState(
                self.model.raw(),
                self.raw.as_ptr(),
                values.as_mut_ptr(),
                SAVED_STATE as i32,
            );
        }
        SavedState {
            model: Arc::clone(&self.model),
            values,
        }
    }

    /// Puts back a state [`Data::save_state`] saved (keeping the current time), and computes
    /// what derives from it, as [`Data::forward`] does.
    ///
    /// # Panics
    ///
    /// When `state` was saved from the data of another model.
    #[track_caller]
    pub fn restore_state(&mut self, state: &SavedState) {
        assert!(
            Arc::ptr_eq(&state.model, &self.model),
            "a state restored into the data of a model it was not saved from"
        );
        // SAFETY: model and data belong together; `state.values` was filled by mj_getState
        // with the same signature for the same model, so it holds what mj_setState reads.
        unsafe {
            self.model.mj().mj_setState(
                self.model.raw(),
                self.raw.as_ptr(),
                state.values.as_ptr(),
                SAVED_STATE as i32,
            );
        }
        self.forward();
    }

    /// Simulation time in seconds.
    pub fn time(&self) -> f64 {
        self.raw().time
    }

    /// All actuator controls, indexed by [`ActuatorId::index`].
    pub fn ctrl(&self) -> &[f64] {
        // SAFETY: ctrl holds nu elements.
        unsafe { self.array(self.raw().ctrl, self.model.nu()) }
    }

    /// Sets the control of one actuator.
    ///
    /// # Panics
    ///
    /// When `actuator` was resolved in a different model.
    #[track_caller]
    pub fn set_ctrl(&mut self, actuator: ActuatorId, value: f64) {
        let index = self.model.index_of(actuator);
        let nu = self.model.nu();
        // SAFETY: ctrl holds nu elements and `index` < nu for an id of this model.
        unsafe { self.array_mut(self.raw().ctrl, nu)[index] = value }
    }

    /// The generalised coordinates of one joint: 7 for a free joint (position, quaternion),
    /// 4 for a ball joint, 1 for a slide or hinge.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn qpos(&self, joint: JointId) -> &[f64] {
        let range = self.joint_range(joint, Coordinates::Position);
        // SAFETY: qpos holds nq elements.
        unsafe { &self.array(self.raw().qpos, self.model.nq())[range] }
    }

    /// Mutable [`Data::qpos`]; call [`Data::forward`] afterwards to update derived quantities.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn qpos_mut(&mut self, joint: JointId) -> &mut [f64] {
        let range = self.joint_range(joint, Coordinates::Position);
        let nq = self.model.nq();
        // SAFETY: qpos holds nq elements.
        unsafe { &mut self.array_mut(self.raw().qpos, nq)[range] }
    }

    /// The generalised velocities of one joint: 6 for a free joint, 3 for a ball, 1 otherwise.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn qvel(&self, joint: JointId) -> &[f64] {
        let range = self.joint_range(joint, Coordinates::Velocity);
        // SAFETY: qvel holds nv elements.
        unsafe { &self.array(self.raw().qvel, self.model.nv())[range] }
    }

    /// Mutable [`Data::qvel`].
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn qvel_mut(&mut self, joint: JointId) -> &mut [f64] {
        let range = self.joint_range(joint, Coordinates::Velocity);
        let nv = self.model.nv();
        // SAFETY: qvel holds nv elements.
        unsafe { &mut self.array_mut(self.raw().qvel, nv)[range] }
    }

    /// The joint-space inertia a hinge or slide joint's first degree of freedom sees (the
    /// diagonal of the mass matrix, armature included; kg·m² or kg) as of the last step.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn dof_inertia(&self, joint: JointId) -> f64 {
        let dof = self.joint_range(joint, Coordinates::Velocity).start;
        let m = self.model.raw();
        let nv = self.model.nv();
        // SAFETY: M_rowadr and M_rownnz hold nv elements; M holds nC, and row `dof` of its
        // lower triangle ends with the diagonal at M_rowadr[dof] + M_rownnz[dof] - 1 < nC.
        unsafe {
            let address =
                self.model.array(m.M_rowadr, nv)[dof] + self.model.array(m.M_rownnz, nv)[dof] - 1;
            self.array(self.raw().M, m.nC as usize)[address as usize]
        }
    }

    /// The force (N·m for a hinge, N for a slide) that gravity, Coriolis and centrifugal
    /// forces put on a hinge or slide joint's first degree of freedom and that nothing in the
    /// model compensates: MuJoCo's bias force less its gravity compensation (bodies'
    /// `gravcomp`), as of the last step. A controller that adds it holds the joint against them.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn dof_bias_force(&self, joint: JointId) -> f64 {
        let dof = self.joint_range(joint, Coordinates::Velocity).start;
        let nv = self.model.nv();
        // SAFETY: qfrc_bias and qfrc_gravcomp hold nv elements and `dof` < nv.
        unsafe {
            self.array(self.raw().qfrc_bias, nv)[dof]
                - self.array(self.raw().qfrc_gravcomp, nv)[dof]
        }
    }

    /// An actuator's length — its transmission's position times its gear (a joint's angle or
    /// travel, a tendon's length) — and the rate it changes at, as of the last step.
    ///
    /// # Panics
    ///
    /// When `actuator` was resolved in a different model.
    #[track_caller]
    pub fn actuator_length(&self, actuator: ActuatorId) -> (f64, f64) {
        let index = self.model.index_of(actuator);
        let nu = self.model.nu();
        // SAFETY: actuator_length and actuator_velocity hold nu elements and `index` < nu.
        unsafe {
            (
                self.array(self.raw().actuator_length, nu)[index],
                self.array(self.raw().actuator_velocity, nu)[index],
            )
        }
    }

    /// The reading of one sensor, as many values as the sensor's dimension (3 for an
    /// accelerometer, 1 for a joint position sensor, …).
    ///
    /// # Panics
    ///
    /// When `sensor` was resolved in a different model.
    #[track_caller]
    pub fn sensor(&self, sensor: SensorId) -> &[f64] {
        let index = self.model.index_of(sensor);
        let m = self.model.raw();
        let count = self.model.count(crate::ObjectKind::Sensor);
        // SAFETY: sensor_adr and sensor_dim hold nsensor elements; sensordata nsensordata.
        unsafe {
            let start = to_usize(self.model.array(m.sensor_adr, count)[index]);
            let dim = to_usize(self.model.array(m.sensor_dim, count)[index]);
            &self.array(self.raw().sensordata, to_usize(m.nsensordata))[start..start + dim]
        }
    }

    /// The index of a joint's first degree of freedom among the model's `nv` (its column in
    /// [`Data::point_jacobian`]).
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn dof(&self, joint: JointId) -> usize {
        self.joint_range(joint, Coordinates::Velocity).start
    }

    /// How a point fixed to `body`, at `point` in world coordinates now, moves with each degree
    /// of freedom (MuJoCo's `mj_jac`): per degree of freedom, the point's velocity per unit of
    /// its velocity. A force `f` at the point is, on degree of freedom `i`, the generalised
    /// force `jacobian[i] · f`. As of the last step or [`Data::forward`].
    ///
    /// # Panics
    ///
    /// When `body` was resolved in a different model.
    #[track_caller]
    pub fn point_jacobian(&self, body: BodyId, point: [f64; 3]) -> Vec<[f64; 3]> {
        let index = self.model.index_of(body);
        let nv = self.model.nv();
        let mut rows = vec![0.0; 3 * nv];
        // SAFETY: model and data belong together; `rows` holds the 3·nv numbers mj_jac writes,
        // jacr may be null, `point` holds 3 and `index` < nbody.
        unsafe {
            self.model.mj().mj_jac(
                self.model.raw(),
                self.raw(),
                rows.as_mut_ptr(),
                std::ptr::null_mut(),
                point.as_ptr(),
                index as i32,
            );
        }
        (0..nv)
            .map(|dof| [rows[dof], rows[nv + dof], rows[2 * nv + dof]])
            .collect()
    }

    /// How a site moves with each degree of freedom (MuJoCo's `mj_jacSite`), written into
    /// `translation` and `rotation` as 3 rows of `nv` numbers each (world coordinates): row `r`,
    /// degree of freedom `i` is the site's linear (angular) velocity along axis `r` per unit of
    /// that degree of freedom's velocity. As of the last step, [`Data::forward`] or
    /// [`Data::kinematics`]. The vectors are resized to 3·nv.
    ///
    /// # Panics
    ///
    /// When `site` was resolved in a different model.
    #[track_caller]
    pub fn site_jacobian(&self, site: SiteId, translation: &mut Vec<f64>, rotation: &mut Vec<f64>) {
        let index = self.model.index_of(site);
        self.frame_jacobian(self.model.mj().mj_jacSite, index, translation, rotation);
    }

    /// As [`Data::site_jacobian`], for the frame of `body` (MuJoCo's `mj_jacBody`).
    ///
    /// # Panics
    ///
    /// When `body` was resolved in a different model.
    #[track_caller]
    pub fn body_jacobian(&self, body: BodyId, translation: &mut Vec<f64>, rotation: &mut Vec<f64>) {
        let index = self.model.index_of(body);
        self.frame_jacobian(self.model.mj().mj_jacBody, index, translation, rotation);
    }

    /// The Jacobian MuJoCo's `jacobian` (`mj_jacSite`, `mj_jacBody`) writes for object `index`
    /// of its kind, into buffers resized to 3·nv.
    fn frame_jacobian(
        &self,
        jacobian: FrameJacobian,
        index: usize,
        translation: &mut Vec<f64>,
        rotation: &mut Vec<f64>,
    ) {
        let nv = self.model.nv();
        translation.resize(3 * nv, 0.0);
        rotation.resize(3 * nv, 0.0);
        // SAFETY: model and data belong together; both buffers hold the 3·nv numbers the
        // function writes, and `index` was resolved in this model for the function's kind.
        unsafe {
            jacobian(
                self.model.raw(),
                self.raw(),
                translation.as_mut_ptr(),
                rotation.as_mut_ptr(),
                index as i32,
            );
        }
    }

    /// The product of the joint-space inertia matrix and `vector` (MuJoCo's `mj_mulM`), nv
    /// numbers each: the generalised force that gives the accelerations `vector`, as of the
    /// last step or [`Data::forward`].
    ///
    /// # Panics
    ///
    /// When either slice does not hold nv numbers.
    #[track_caller]
    pub fn inertia_times(&self, vector: &[f64], result: &mut [f64]) {
        let nv = self.model.nv();
        assert!(
            vector.len() == nv && result.len() == nv,
            "inertia_times takes nv = {nv} numbers"
        );
        // SAFETY: model and data belong together; both slices hold nv numbers.
        unsafe {
            self.model.mj().mj_mulM(
                self.model.raw(),
                self.raw(),
                result.as_mut_ptr(),
                vector.as_ptr(),
            );
        }
    }

    /// Where a hinge or slide joint is in world coordinates: a point on its axis (its anchor)
    /// and the axis's unit direction, as computed by the last [`Data::step`] or
    /// [`Data::forward`]; see [`Data::body_pose`].
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn joint_axis(&self, joint: JointId) -> ([f64; 3], [f64; 3]) {
        let index = self.model.index_of(joint);
        let njnt = self.model.count(crate::ObjectKind::Joint);
        // SAFETY: xanchor and xaxis hold 3·njnt elements.
        let (anchor, axis) = unsafe {
            (
                self.array(self.raw().xanchor, 3 * njnt),
                self.array(self.raw().xaxis, 3 * njnt),
            )
        };
        let three = |values: &[f64]| {
            [
                values[3 * index],
                values[3 * index + 1],
                values[3 * index + 2],
            ]
        };
        (three(anchor), three(axis))
    }

    /// The pose of a body in world coordinates, as computed by the last [`Data::step`] or
    /// [`Data::forward`]. A step computes positions *before* integrating, so after a step the
    /// pose lags `qpos` by one timestep; call `forward` first when that matters.
    ///
    /// # Panics
    ///
    /// When `body` was resolved in a different model.
    #[track_caller]
    pub fn body_pose(&self, body: BodyId) -> Pose {
        let index = self.model.index_of(body);
        let nbody = self.model.count(crate::ObjectKind::Body);
        // SAFETY: xpos holds 3·nbody elements and xquat 4·nbody.
        let (xpos, xquat) = unsafe {
            (
                self.array(self.raw().xpos, 3 * nbody),
                self.array(self.raw().xquat, 4 * nbody),
            )
        };
        Pose::of(xpos, xquat, index)
    }

    /// The pose of a site in world coordinates (a tool centre point, a mounting point), as
    /// computed by the last [`Data::step`] or [`Data::forward`]; see [`Data::body_pose`].
    ///
    /// # Panics
    ///
    /// When `site` was resolved in a different model.
    #[track_caller]
    pub fn site_pose(&self, site: SiteId) -> Pose {
        let index = self.model.index_of(site);
        let nsite = self.model.count(crate::ObjectKind::Site);
        // SAFETY: site_xpos holds 3·nsite elements and site_xmat 9·nsite.
        let (xpos, xmat) = unsafe {
            (
                self.array(self.raw().site_xpos, 3 * nsite),
                self.array(self.raw().site_xmat, 9 * nsite),
            )
        };
        self.pose_of_frame(xpos, xmat, index)
    }

    /// The distance between the surfaces of two geoms (negative when they overlap), up to
    /// `most` (beyond which `most` is returned), as of the last [`Data::step`],
    /// [`Data::forward`] or [`Data::kinematics`].
    ///
    /// # Panics
    ///
    /// When a geom was resolved in a different model.
    #[track_caller]
    pub fn geom_distance(&mut self, first: GeomId, second: GeomId, most: f64) -> f64 {
        let (a, b) = (self.model.index_of(first), self.model.index_of(second));
        let mut from_to = [0.0; 6];
        // SAFETY: model and data belong together; both indices are below ngeom; `from_to`
        // holds the 6 numbers MuJoCo writes.
        unsafe {
            self.model.mj().mj_geomDistance(
                self.model.raw(),
                self.raw.as_ptr(),
                a as std::os::raw::c_int,
                b as std::os::raw::c_int,
                most,
                from_to.as_mut_ptr(),
            )
        }
    }

    /// The gap between two bodies' surfaces: the least [`Data::geom_distance`] between their
    /// colliding geoms (negative where they overlap), up to 1 m; `None` when either has no
    /// colliding geom.
    ///
    /// # Panics
    ///
    /// When a body was resolved in a different model.
    #[track_caller]
    pub fn body_gap(&mut self, first: BodyId, second: BodyId) -> Option<f64> {
        let model = Arc::clone(&self.model);
        let colliding = |body: BodyId| -> Vec<GeomId> {
            model
                .body_geoms(body)
                .into_iter()
                .filter(|&geom| model.geom_collides(geom))
                .collect()
        };
        let (mine, theirs) = (colliding(first), colliding(second));
        mine.iter()
            .flat_map(|&a| theirs.iter().map(move |&b| (a, b)))
            .map(|(a, b)| self.geom_distance(a, b, 1.0))
            .reduce(f64::min)
    }

    /// The pose of a camera in world coordinates, as computed by the last [`Data::step`] or
    /// [`Data::forward`]; see [`Data::body_pose`]. MuJoCo's cameras look down their frame's −z
    /// axis, +y up in the image.
    ///
    /// # Panics
    ///
    /// When `camera` was resolved in a different model.
    #[track_caller]
    pub fn camera_pose(&self, camera: CameraId) -> Pose {
        let index = self.model.index_of(camera);
        let ncam = self.model.count(crate::ObjectKind::Camera);
        // SAFETY: cam_xpos holds 3·ncam elements and cam_xmat 9·ncam.
        let (xpos, xmat) = unsafe {
            (
                self.array(self.raw().cam_xpos, 3 * ncam),
                self.array(self.raw().cam_xmat, 9 * ncam),
            )
        };
        self.pose_of_frame(xpos, xmat, index)
    }

    /// The `index`th pose of MuJoCo arrays of positions (3 numbers each) and rotation matrices
    /// (9).
    fn pose_of_frame(&self, xpos: &[f64], xmat: &[f64], index: usize) -> Pose {
        let mut quat = [0.0; 4];
        // SAFETY: `quat` holds 4 numbers and the matrix 9, as mju_mat2Quat reads and writes.
        unsafe {
            self.model
                .mj()
                .mju_mat2Quat(quat.as_mut_ptr(), xmat[9 * index..].as_ptr());
        }
        Pose {
            pos: [xpos[3 * index], xpos[3 * index + 1], xpos[3 * index + 2]],
            quat,
        }
    }

    /// How many times MuJoCo has raised each kind of warning since this state was made or
    /// reset: compared before and after a step, what went wrong in it.
    pub fn warnings(&self) -> crate::Warnings {
        crate::Warnings::of(self.raw())
    }

    /// The raw `mjData`, for what the safe layer does not cover yet.
    pub fn ffi(&self) -> &sys::mjData {
        self.raw()
    }

    #[cfg(feature = "render")]
    pub(crate) fn raw_mut_ptr(&mut self) -> *mut sys::mjData {
        self.raw.as_ptr()
    }

    fn raw(&self) -> &sys::mjData {
        // SAFETY: `raw` points to the mjData this value owns until drop.
        unsafe { self.raw.as_ref() }
    }

    /// # Safety
    ///
    /// `array` must be one of this data's arrays with at least `len` elements.
    unsafe fn array(&self, array: *const f64, len: usize) -> &[f64] {
        // SAFETY: forwarded to the caller; the arrays live as long as `self`.
        unsafe { self.model.array(array, len) }
    }

    /// # Safety
    ///
    /// `array` must be one of this data's arrays with at least `len` elements.
    unsafe fn array_mut(&mut self, array: *mut f64, len: usize) -> &mut [f64] {
        if len == 0 {
            return &mut [];
        }
        // SAFETY: forwarded to the caller; `&mut self` makes the borrow exclusive.
        unsafe { std::slice::from_raw_parts_mut(array, len) }
    }

    #[track_caller]
    fn joint_range(&self, joint: JointId, coordinates: Coordinates) -> std::ops::Range<usize> {
        let index = self.model.index_of(joint);
        let m = self.model.raw();
        let njnt = self.model.count(crate::ObjectKind::Joint);
        // SAFETY: jnt_type, jnt_qposadr and jnt_dofadr hold njnt elements.
        let (kind, qpos_adr, dof_adr) = unsafe {
            (
                self.model.array(m.jnt_type, njnt)[index],
                self.model.array(m.jnt_qposadr, njnt)[index],
                self.model.array(m.jnt_dofadr, njnt)[index],
            )
        };
        let (positions, velocities) = match kind as u32 {
            sys::mjJNT_FREE => (7, 6),
            sys::mjJNT_BALL => (4, 3),
            _ => (1, 1),
        };
        match coordinates {
            Coordinates::Position => to_usize(qpos_adr)..to_usize(qpos_adr) + positions,
            Coordinates::Velocity => to_usize(dof_adr)..to_usize(dof_adr) + velocities,
        }
    }
}

#[derive(Clone, Copy)]
enum Coordinates {
    Position,
    Velocity,
}

impl Drop for Data {
    fn drop(&mut self) {
        // SAFETY: the pointer came from mj_makeData and is freed exactly once, here.
        unsafe { self.model.mj().mj_deleteData(self.raw.as_ptr()) }
    }
}

impl fmt::Debug for Data {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Data")
            .field("time", &self.time())
            .field("model", &self.model)
            .finish()
    }
}
