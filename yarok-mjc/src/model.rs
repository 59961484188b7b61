//! [`Model`]: a compiled MuJoCo model, built from MJCF text or a file.

use std::ffi::{CStr, CString, c_char};
use std::fmt;
use std::path::Path;
use std::ptr::NonNull;

use crate::error::ModelError;
use crate::guard;
use crate::library::mujoco;
use crate::pose::Pose;
use crate::sys;
use crate::vfs::Vfs;

/// The size of the buffer MuJoCo writes load errors into.
const ERROR_CAPACITY: usize = 1024;
/// The name the MJCF text gets inside the virtual file system; assets are found relative to it.
const MAIN_FILE: &str = "__yarok_main__.xml";

/// A compiled MuJoCo model (`mjModel`): the immutable description of a world.
///
/// A model is shared by the [`Data`](crate::Data) that simulate it, so it is usually held in an
/// [`Arc`](std::sync::Arc). Names are resolved to typed ids ([`JointId`], [`SensorId`], …) once;
/// the ids then index into `Data` without string lookups.
///
/// # Examples
///
/// ```
/// use yarok_mjc::Model;
///
/// let model = Model::from_xml_str(
///     r#"<mujoco><worldbody><body name="ball"><freejoint/><geom size="0.1"/></body></worldbody></mujoco>"#,
/// )?;
/// assert_eq!(model.nq(), 7);
/// assert_eq!(model.body("ball")?.index(), 1);
/// # Ok::<(), yarok_mjc::ModelError>(())
/// ```
pub struct Model {
    raw: NonNull<sys::mjModel>,
    mj: &'static sys::MuJoCo,
}

// SAFETY: a Model owns its mjModel and never hands out mutable access to it after compilation, so
// moving it to another thread cannot race with anything.
unsafe impl Send for Model {}
// SAFETY: every function reached through `&Model` only reads the mjModel (`const mjModel*` in
// MuJoCo's API), and MuJoCo supports concurrent reads of one model (its own threaded rollouts
// share one mjModel).
unsafe impl Sync for Model {}

impl Model {
    /// Compiles MJCF text that needs no files beyond the ones it names by absolute path.
    ///
    /// # Errors
    ///
    /// [`ModelError::Compile`] with MuJoCo's message when the XML is malformed or does not
    /// compile; [`ModelError::Library`] when libmujoco is unavailable.
    pub fn from_xml_str(xml: &str) -> Result<Self, ModelError> {
        Self::from_xml_str_with_assets(xml, std::iter::empty::<(&str, &[u8])>())
    }

    /// Compiles MJCF text whose meshes, textures and included files are given in memory.
    ///
    /// Each asset is `(name, bytes)` where `name` is the path the MJCF uses for it, relative to
    /// the model (`meshdir`/`texturedir` included), e.g. `("meshes/link.stl", bytes)`.
    ///
    /// # Errors
    ///
    /// As [`Model::from_xml_str`], plus [`ModelError::Asset`] for a repeated asset name.
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_mjc::Model;
    ///
    /// let mesh = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    /// let model = Model::from_xml_str_with_assets(
    ///     r#"<mujoco><asset><mesh file="parts/tetra.obj"/></asset>
    ///        <worldbody><geom type="mesh" mesh="tetra"/></worldbody></mujoco>"#,
    ///     [("parts/tetra.obj", mesh.as_bytes())],
    /// )?;
    /// assert_eq!(model.count(yarok_mjc::ObjectKind::Geom), 1);
    /// # Ok::<(), yarok_mjc::ModelError>(())
    /// ```
    pub fn from_xml_str_with_assets<I, N, B>(xml: &str, assets: I) -> Result<Self, ModelError>
    where
        I: IntoIterator<Item = (N, B)>,
        N: AsRef<str>,
        B: AsRef<[u8]>,
    {
        guard::refuse_known_aborts(xml, "<string>")?;
        Self::compile_xml(xml, assets)
    }

    /// Compiles MJCF text that [`guard`] has seen.
    pub(crate) fn compile_xml<I, N, B>(xml: &str, assets: I) -> Result<Self, ModelError>
    where
        I: IntoIterator<Item = (N, B)>,
        N: AsRef<str>,
        B: AsRef<[u8]>,
    {
        let mj = mujoco()?;
        let mut vfs = Vfs::new(mj);
        vfs.add(MAIN_FILE, xml.as_bytes())?;
        for (name, bytes) in assets {
            vfs.add(name.as_ref(), bytes.as_ref())?;
        }
        load(mj, MAIN_FILE, Some(&vfs), "<string>")
    }

    /// A model from MuJoCo's binary format ([`Model::to_binary`]), written by this MuJoCo
    /// version.
    ///
    /// # Errors
    ///
    /// [`ModelError::Compile`] when MuJoCo does not accept the bytes.
    pub fn from_binary(bytes: &[u8]) -> Result<Self, ModelError> {
        let mj = mujoco()?;
        let size = sys::mjtSize::try_from(bytes.len()).unwrap_or(sys::mjtSize::MAX);
        // SAFETY: the buffer holds `size` bytes and outlives the call, which copies from it.
        let raw = unsafe { mj.mj_loadModelBuffer(bytes.as_ptr().cast(), size) };
        NonNull::new(raw)
            .map(|raw| Model { raw, mj })
            .ok_or_else(|| ModelError::Compile {
                origin: "a binary model".into(),
                message: "MuJoCo could not read it (another version's, or damaged)".into(),
            })
    }

    /// Compiles an MJCF (or URDF) file; the files it names are read relative to its folder.
    ///
    /// # Errors
    ///
    /// As [`Model::from_xml_str`]; a missing file is a [`ModelError::Compile`] naming it.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, ModelError> {
        let path = path.as_ref();
        if let Ok(xml) = std::fs::read_to_string(path) {
            guard::refuse_known_aborts(&xml, &path.display().to_string())?;
        }
        load(
            mujoco()?,
            &path.to_string_lossy(),
            None,
            &path.display().to_string(),
        )
    }

    /// The simulation timestep in seconds (`option/@timestep`).
    pub fn timestep(&self) -> f64 {
        self.raw().opt.timestep
    }

    /// Number of generalised coordinates (length of `qpos`).
    pub fn nq(&self) -> usize {
        to_usize(self.raw().nq)
    }

    /// Number of degrees of freedom (length of `qvel`).
    pub fn nv(&self) -> usize {
        to_usize(self.raw().nv)
    }

    /// Number of actuators (length of `ctrl`).
    pub fn nu(&self) -> usize {
        to_usize(self.raw().nu)
    }

    /// How many objects of a kind the model has; the world body counts as body 0.
    pub fn count(&self, kind: ObjectKind) -> usize {
        let m = self.raw();
        to_usize(match kind {
            ObjectKind::Body => m.nbody,
            ObjectKind::Joint => m.njnt,
            ObjectKind::Geom => m.ngeom,
            ObjectKind::Site => m.nsite,
            ObjectKind::Camera => m.ncam,
            ObjectKind::Actuator => m.nu,
            ObjectKind::Sensor => m.nsensor,
            ObjectKind::Tendon => m.ntendon,
            ObjectKind::Keyframe => m.nkey,
            ObjectKind::Equality => m.neq,
        })
    }

    /// The parent of a body; the world body is its own parent.
    ///
    /// # Panics
    ///
    /// When `body` was resolved in a different model.
    #[track_caller]
    pub fn body_parent(&self, body: BodyId) -> BodyId {
        let index = self.index_of(body);
        // SAFETY: body_parentid holds nbody entries and `index` < nbody.
        let parent =
            unsafe { self.array(self.raw().body_parentid, self.count(ObjectKind::Body)) }[index];
        self.body_at(parent)
    }

    /// Whether `body` is `carrier` or hangs below it in the kinematic tree.
    ///
    /// # Panics
    ///
    /// When either body was resolved in a different model.
    #[track_caller]
    pub fn carries(&self, carrier: BodyId, mut body: BodyId) -> bool {
        loop {
            if body == carrier {
                return true;
            }
            let parent = self.body_parent(body);
            if parent == body {
                return false;
            }
            body = parent;
        }
    }

    /// The body a joint moves.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn joint_body(&self, joint: JointId) -> BodyId {
        let index = self.index_of(joint);
        // SAFETY: jnt_bodyid holds njnt entries and `index` < njnt.
        let body =
            unsafe { self.array(self.raw().jnt_bodyid, self.count(ObjectKind::Joint)) }[index];
        self.body_at(body)
    }

    /// The body a site is on.
    ///
    /// # Panics
    ///
    /// When `site` was resolved in a different model.
    #[track_caller]
    pub fn site_body(&self, site: SiteId) -> BodyId {
        let index = self.index_of(site);
        // SAFETY: site_bodyid holds nsite entries and `index` < nsite.
        let body =
            unsafe { self.array(self.raw().site_bodyid, self.count(ObjectKind::Site)) }[index];
        self.body_at(body)
    }

    /// The geoms a body carries.
    ///
    /// # Panics
    ///
    /// When `body` was resolved in a different model.
    #[track_caller]
    pub fn body_geoms(&self, body: BodyId) -> Vec<GeomId> {
        let index = self.index_of(body);
        let nbody = self.count(ObjectKind::Body);
        // SAFETY: body_geomadr and body_geomnum hold nbody entries.
        let (first, count) = unsafe {
            (
                self.array(self.raw().body_geomadr, nbody)[index],
                self.array(self.raw().body_geomnum, nbody)[index],
            )
        };
        (0..count.max(0))
            .map(|offset| GeomId {
                index: to_usize(first + offset),
                signature: self.signature(),
            })
            .collect()
    }

    /// Whether a geom takes part in collisions (its `contype` or `conaffinity` is not 0), as
    /// a finger's pad does and a purely visual mesh does not.
    ///
    /// # Panics
    ///
    /// When `geom` was resolved in a different model.
    #[track_caller]
    pub fn geom_collides(&self, geom: GeomId) -> bool {
        let index = self.index_of(geom);
        let ngeom = self.count(ObjectKind::Geom);
        // SAFETY: geom_contype and geom_conaffinity hold ngeom entries.
        unsafe {
            self.array(self.raw().geom_contype, ngeom)[index] != 0
                || self.array(self.raw().geom_conaffinity, ngeom)[index] != 0
        }
    }

    /// A copy of the model in which only the geoms of `bodies` collide (with each other), to
    /// study a mechanism's own motion — a gripper's stroke, its fingers meeting — apart from
    /// the objects around it. Ids resolved in this model are valid in the copy.
    ///
    /// # Errors
    ///
    /// [`ModelError::Compile`] when MuJoCo cannot allocate the copy.
    pub fn colliding_only(&self, bodies: &[BodyId]) -> Result<Model, ModelError> {
        let kept: Vec<usize> = bodies.iter().map(|&body| self.index_of(body)).collect();
        // SAFETY: with a null destination, mj_copyModel allocates a deep copy of the live model.
        let raw = unsafe {
            self.mj
                .mj_copyModel(std::ptr::null_mut(), self.raw.as_ptr())
        };
        let raw = NonNull::new(raw).ok_or_else(|| ModelError::Compile {
            origin: "a copy of a model".into(),
            message: "MuJoCo could not allocate it".into(),
        })?;
        let ngeom = self.count(ObjectKind::Geom);
        // SAFETY: the copy is owned here alone, not yet shared, so writing it races with
        // nothing; its geom arrays hold ngeom entries, as the original's.
        unsafe {
            let copy = &mut *raw.as_ptr();
            let bodies = std::slice::from_raw_parts(copy.geom_bodyid, ngeom);
            let types = std::slice::from_raw_parts_mut(copy.geom_contype, ngeom);
            let affinities = std::slice::from_raw_parts_mut(copy.geom_conaffinity, ngeom);
            for geom in 0..ngeom {
                if !kept.contains(&to_usize(bodies[geom])) {
                    types[geom] = 0;
                    affinities[geom] = 0;
                }
            }
        }
        Ok(Model { raw, mj: self.mj })
    }

    /// The id of the body at `index` in this model's arrays (as its `*_bodyid` arrays hold).
    fn body_at(&self, index: std::os::raw::c_int) -> BodyId {
        BodyId {
            index: to_usize(index),
            signature: self.signature(),
        }
    }

    /// A geom's size parameters (their meaning depends on its type: radius, half-lengths, …).
    ///
    /// # Panics
    ///
    /// When `geom` was resolved in a different model.
    #[track_caller]
    pub fn geom_size(&self, geom: GeomId) -> [f64; 3] {
        let index = self.index_of(geom);
        // SAFETY: geom_size holds 3·ngeom entries and `index` < ngeom.
        let sizes = unsafe { self.array(self.raw().geom_size, 3 * self.count(ObjectKind::Geom)) };
        [sizes[3 * index], sizes[3 * index + 1], sizes[3 * index + 2]]
    }

    /// An actuator's gains if it is a position servo on a joint or a tendon (a fixed gain and
    /// an affine bias, as `<position>` and Menagerie's `<general … biastype="affine">` servos
    /// are), `None` otherwise.
    ///
    /// # Panics
    ///
    /// When `actuator` was resolved in a different model.
    #[track_caller]
    pub fn servo_gains(&self, actuator: ActuatorId) -> Option<ServoGains> {
        let index = self.index_of(actuator);
        let nu = self.count(ObjectKind::Actuator);
        let (gains, biases) = (sys::mjNGAIN as usize, sys::mjNBIAS as usize);
        // SAFETY: the type and limit arrays hold nu entries, gainprm nu·mjNGAIN, biasprm
        // nu·mjNBIAS, gear 6·nu and forcerange 2·nu; `index` < nu.
        let (transmission, gain_type, bias_type, gainprm, biasprm, gear, limited, range) = unsafe {
            let m = self.raw();
            (
                self.array(m.actuator_trntype, nu)[index],
                self.array(m.actuator_gaintype, nu)[index],
                self.array(m.actuator_biastype, nu)[index],
                &self.array(m.actuator_gainprm, nu * gains)[index * gains..],
                &self.array(m.actuator_biasprm, nu * biases)[index * biases..],
                self.array(m.actuator_gear, 6 * nu)[6 * index],
                self.array(m.actuator_forcelimited, nu)[index],
                &self.array(m.actuator_forcerange, 2 * nu)[2 * index..2 * index + 2],
            )
        };
        let scalar = [sys::mjTRN_JOINT, sys::mjTRN_TENDON].contains(&(transmission as u32));
        let servo = scalar
            && gain_type == sys::mjGAIN_FIXED as i32
            && bias_type == sys::mjBIAS_AFFINE as i32
            && gainprm[0] > 0.0
            && gear != 0.0;
        servo.then(|| ServoGains {
            gain: gainprm[0],
            kp: -biasprm[1],
            kv: -biasprm[2],
            gear,
            force_range: limited.then(|| [range[0], range[1]]),
        })
    }

    /// The range an actuator's control is clamped to (`ctrlrange`), or `None` when it is not
    /// limited.
    ///
    /// # Panics
    ///
    /// When `actuator` was resolved in a different model.
    #[track_caller]
    pub fn ctrl_range(&self, actuator: ActuatorId) -> Option<[f64; 2]> {
        let index = self.index_of(actuator);
        let nu = self.count(ObjectKind::Actuator);
        // SAFETY: actuator_ctrllimited holds nu entries and actuator_ctrlrange 2·nu.
        let (limited, range) = unsafe {
            (
                self.array(self.raw().actuator_ctrllimited, nu)[index],
                self.array(self.raw().actuator_ctrlrange, 2 * nu),
            )
        };
        limited.then(|| [range[2 * index], range[2 * index + 1]])
    }

    /// The gear of a motor on a joint — an actuator whose force is gear × control, with no
    /// bias (`<motor>`, or `<general>` so set) — or `None` for any other actuator.
    ///
    /// # Panics
    ///
    /// When `actuator` was resolved in a different model.
    #[track_caller]
    pub fn motor_gear(&self, actuator: ActuatorId) -> Option<f64> {
        let index = self.index_of(actuator);
        let nu = self.count(ObjectKind::Actuator);
        let gains = sys::mjNGAIN as usize;
        // SAFETY: the type arrays hold nu entries, gainprm nu·mjNGAIN and gear 6·nu.
        let (transmission, gain_type, bias_type, gain, gear) = unsafe {
            let m = self.raw();
            (
                self.array(m.actuator_trntype, nu)[index],
                self.array(m.actuator_gaintype, nu)[index],
                self.array(m.actuator_biastype, nu)[index],
                self.array(m.actuator_gainprm, nu * gains)[index * gains],
                self.array(m.actuator_gear, 6 * nu)[6 * index],
            )
        };
        let motor = transmission as u32 == sys::mjTRN_JOINT
            && gain_type == sys::mjGAIN_FIXED as i32
            && bias_type == sys::mjBIAS_NONE as i32
            && gain == 1.0
            && gear != 0.0;
        motor.then_some(gear)
    }

    /// A joint's limits (radians for hinge and ball joints, metres for slide joints), or `None`
    /// when it is not limited.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn joint_range(&self, joint: JointId) -> Option<[f64; 2]> {
        let index = self.index_of(joint);
        let njnt = self.count(ObjectKind::Joint);
        // SAFETY: jnt_limited holds njnt entries and jnt_range 2·njnt.
        let (limited, range) = unsafe {
            (
                self.array(self.raw().jnt_limited, njnt)[index],
                self.array(self.raw().jnt_range, 2 * njnt),
            )
        };
        limited.then(|| [range[2 * index], range[2 * index + 1]])
    }

    /// How a hinge or slide joint's degree of freedom resists motion by itself: its viscous
    /// damping, dry friction and armature ([`JointLosses`]).
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn joint_losses(&self, joint: JointId) -> JointLosses {
        let index = self.index_of(joint);
        let (njnt, nv) = (self.count(ObjectKind::Joint), self.nv());
        let (nref, nimp) = (sys::mjNREF as usize, sys::mjNIMP as usize);
        // SAFETY: jnt_dofadr holds njnt entries, each a degree of freedom below nv (or -1 for
        // none, filtered out); the dof arrays hold nv entries, dof_solref nv·mjNREF and
        // dof_solimp nv·mjNIMP.
        let (damping, frictionloss, armature, solref, solimp, invweight) = unsafe {
            let m = self.raw();
            let Ok(dof) = usize::try_from(self.array(m.jnt_dofadr, njnt)[index]) else {
                return JointLosses::default();
            };
            (
                self.array(m.dof_damping, nv)[dof],
                self.array(m.dof_frictionloss, nv)[dof],
                self.array(m.dof_armature, nv)[dof],
                &self.array(m.dof_solref, nv * nref)[dof * nref..(dof + 1) * nref],
                &self.array(m.dof_solimp, nv * nimp)[dof * nimp..(dof + 1) * nimp],
                self.array(m.dof_invweight0, nv)[dof],
            )
        };
        // MuJoCo's soft constraint at zero violation, as mj_makeImpedance sets it up: the
        // impedance is solimp's dmin, the regularizer (1 - d)/d times the dof's inverse weight,
        // the reference acceleration -b·v with b = 2/(dmax·timeconst) (the time constant at
        // least two steps unless refsafe is off), or -solref[1] in the direct form.
        let d = solimp[0].clamp(sys::mjMINIMP, sys::mjMAXIMP);
        let dmax = solimp[1].clamp(sys::mjMINIMP, sys::mjMAXIMP);
        let refsafe = self.raw().opt.disableflags & sys::mjDSBL_REFSAFE as i32 == 0;
        let timeconst = if refsafe {
            solref[0].max(2.0 * self.timestep())
        } else {
            solref[0]
        };
        let friction_damping = if solref[0] > 0.0 {
            2.0 / (dmax * timeconst)
        } else {
            -solref[1]
        };
        JointLosses {
            damping,
            frictionloss,
            armature,
            friction_regularizer: ((1.0 - d) / d * invweight).max(sys::mjMINVAL),
            friction_damping,
        }
    }

    /// The range the force of every actuator on a joint together is clamped to
    /// (`actuatorfrcrange`), or `None` when it is not limited.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn joint_force_range(&self, joint: JointId) -> Option<[f64; 2]> {
        let index = self.index_of(joint);
        let njnt = self.count(ObjectKind::Joint);
        // SAFETY: jnt_actfrclimited holds njnt entries and jnt_actfrcrange 2·njnt.
        let (limited, range) = unsafe {
            (
                self.array(self.raw().jnt_actfrclimited, njnt)[index],
                self.array(self.raw().jnt_actfrcrange, 2 * njnt),
            )
        };
        limited.then(|| [range[2 * index], range[2 * index + 1]])
    }

    /// The range an actuator's force is clamped to (`forcerange`), or `None` when it is not
    /// limited.
    ///
    /// # Panics
    ///
    /// When `actuator` was resolved in a different model.
    #[track_caller]
    pub fn actuator_force_range(&self, actuator: ActuatorId) -> Option<[f64; 2]> {
        let index = self.index_of(actuator);
        let nu = self.count(ObjectKind::Actuator);
        // SAFETY: actuator_forcelimited holds nu entries and actuator_forcerange 2·nu.
        let (limited, range) = unsafe {
            (
                self.array(self.raw().actuator_forcelimited, nu)[index],
                self.array(self.raw().actuator_forcerange, 2 * nu),
            )
        };
        limited.then(|| [range[2 * index], range[2 * index + 1]])
    }

    /// The joint an actuator drives directly (its transmission is a joint), or `None` for a
    /// tendon, site or other transmission.
    ///
    /// # Panics
    ///
    /// When `actuator` was resolved in a different model.
    #[track_caller]
    pub fn actuator_joint(&self, actuator: ActuatorId) -> Option<JointId> {
        let index = self.index_of(actuator);
        let nu = self.count(ObjectKind::Actuator);
        // SAFETY: actuator_trntype holds nu entries and actuator_trnid 2·nu.
        let (transmission, target) = unsafe {
            (
                self.array(self.raw().actuator_trntype, nu)[index],
                self.array(self.raw().actuator_trnid, 2 * nu)[2 * index],
            )
        };
        let joint = usize::try_from(target).ok()?;
        (transmission as u32 == sys::mjTRN_JOINT).then(|| JointId {
            index: joint,
            signature: self.signature(),
        })
    }

    /// A body's pose in its parent's frame, as compiled (`body_pos`, `body_quat`).
    ///
    /// # Panics
    ///
    /// When `body` was resolved in a different model.
    #[track_caller]
    pub fn body_local_pose(&self, body: BodyId) -> Pose {
        let index = self.index_of(body);
        let nbody = self.count(ObjectKind::Body);
        // SAFETY: body_pos holds 3·nbody entries and body_quat 4·nbody.
        let (pos, quat) = unsafe {
            (
                self.array(self.raw().body_pos, 3 * nbody),
                self.array(self.raw().body_quat, 4 * nbody),
            )
        };
        Pose::of(pos, quat, index)
    }

    /// Every body's mass as compiled (kilograms, the world body's 0 first), in MuJoCo's order.
    pub fn body_masses(&self) -> &[f64] {
        // SAFETY: body_mass holds nbody entries.
        unsafe { self.array(self.raw().body_mass, self.count(ObjectKind::Body)) }
    }

    /// The model's structural signature; ids resolved in one model are only valid for models
    /// with the same signature.
    pub fn signature(&self) -> u64 {
        self.raw().signature
    }

    /// The raw `mjModel`, for what the safe layer does not cover yet.
    pub fn ffi(&self) -> &sys::mjModel {
        self.raw()
    }

    pub(crate) fn raw(&self) -> &sys::mjModel {
        // SAFETY: `raw` points to the mjModel this value owns until drop.
        unsafe { self.raw.as_ref() }
    }

    pub(crate) fn mj(&self) -> &'static sys::MuJoCo {
        self.mj
    }

    /// Reads `len` elements of one of the model's arrays.
    ///
    /// # Safety
    ///
    /// `array` must be one of this model's arrays and hold at least `len` elements.
    pub(crate) unsafe fn array<T>(&self, array: *const T, len: usize) -> &[T] {
        if len == 0 {
            return &[];
        }
        // SAFETY: the caller guarantees `array` is a live model array of `len` elements; the
        // model outlives the returned borrow.
        unsafe { std::slice::from_raw_parts(array, len) }
    }

    /// Every joint, in MuJoCo's order.
    pub fn joints(&self) -> impl Iterator<Item = JointId> + '_ {
        (0..self.count(ObjectKind::Joint)).map(|index| JointId {
            index,
            signature: self.signature(),
        })
    }

    /// A joint's name in the model (`arm/shoulder`), or `None` when it has none.
    ///
    /// # Panics
    ///
    /// When `joint` was resolved in a different model.
    #[track_caller]
    pub fn joint_name(&self, joint: JointId) -> Option<String> {
        self.name_of(ObjectKind::Joint, self.index_of(joint))
    }

    /// Every body but the world body, in MuJoCo's order (parents before their children).
    pub fn bodies(&self) -> impl Iterator<Item = BodyId> + '_ {
        (1..self.count(ObjectKind::Body)).map(|index| BodyId {
            index,
            signature: self.signature(),
        })
    }

    /// A body's name in the model (`arm/flange`), or `None` when it has none.
    ///
    /// # Panics
    ///
    /// When `body` was resolved in a different model.
    #[track_caller]
    pub fn body_name(&self, body: BodyId) -> Option<String> {
        self.name_of(ObjectKind::Body, self.index_of(body))
    }

    /// The welds that tie a mocap body to another body (an end-effector moved by a mocap body
    /// rather than by joint actuators): each weld's name (if any), the mocap body and the body
    /// it holds.
    pub fn mocap_welds(&self) -> Vec<MocapWeld> {
        let m = self.raw();
        let neq = self.count(ObjectKind::Equality);
        let nbody = self.count(ObjectKind::Body);
        // SAFETY: the eq_* arrays hold neq entries and body_mocapid nbody.
        let (types, objtypes, first, second, mocap) = unsafe {
            (
                self.array(m.eq_type, neq),
                self.array(m.eq_objtype, neq),
                self.array(m.eq_obj1id, neq),
                self.array(m.eq_obj2id, neq),
                self.array(m.body_mocapid, nbody),
            )
        };
        let is_mocap = |body: i32| usize::try_from(body).is_ok_and(|b| b < nbody && mocap[b] >= 0);
        (0..neq)
            .filter(|&i| types[i] == sys::mjEQ_WELD as i32 && objtypes[i] == sys::mjOBJ_BODY as i32)
            .filter_map(|i| {
                let (mocap_body, held) = match (is_mocap(first[i]), is_mocap(second[i])) {
                    (true, false) => (first[i], second[i]),
                    (false, true) => (second[i], first[i]),
                    _ => return None,
                };
                Some(MocapWeld {
                    name: self.name_of(ObjectKind::Equality, i),
                    mocap: self.body_at(mocap_body),
                    held: self.body_at(held),
                })
            })
            .collect()
    }

    /// Every camera, in MuJoCo's order.
    pub fn cameras(&self) -> impl Iterator<Item = CameraId> + '_ {
        (0..self.count(ObjectKind::Camera)).map(|index| CameraId {
            index,
            signature: self.signature(),
        })
    }

    /// A camera's name in the model (`arm/gripper/left_digit/camera`), or `None` when it has
    /// none.
    ///
    /// # Panics
    ///
    /// When `camera` was resolved in a different model.
    #[track_caller]
    pub fn camera_name(&self, camera: CameraId) -> Option<String> {
        self.name_of(ObjectKind::Camera, self.index_of(camera))
    }

    /// Every actuator, in MuJoCo's order (the order of [`Data::ctrl`](crate::Data::ctrl)).
    pub fn actuators(&self) -> impl Iterator<Item = ActuatorId> + '_ {
        (0..self.count(ObjectKind::Actuator)).map(|index| ActuatorId {
            index,
            signature: self.signature(),
        })
    }

    /// An actuator's name in the model (`arm/shoulder_pan`), or `None` when it has none.
    ///
    /// # Panics
    ///
    /// When `actuator` was resolved in a different model.
    #[track_caller]
    pub fn actuator_name(&self, actuator: ActuatorId) -> Option<String> {
        self.name_of(ObjectKind::Actuator, self.index_of(actuator))
    }

    /// The name of object `index` of `kind`, if it has one.
    pub(crate) fn name_of(&self, kind: ObjectKind, index: usize) -> Option<String> {
        let index = i32::try_from(index).ok()?;
        // SAFETY: the model pointer is valid and `index` is one of its objects of `kind`.
        let name = unsafe { self.mj.mj_id2name(self.raw.as_ptr(), kind.mj_obj(), index) };
        if name.is_null() {
            return None;
        }
        // SAFETY: MuJoCo returns a NUL-terminated name owned by the model, alive while it is.
        let name = unsafe { std::ffi::CStr::from_ptr(name) };
        Some(name.to_string_lossy().into_owned())
    }

    fn id(&self, kind: ObjectKind, name: &str) -> Result<usize, ModelError> {
        let c_name = CString::new(name).map_err(|_| ModelError::InteriorNul {
            what: format!("{kind} name {name:?}"),
        })?;
        // SAFETY: the model pointer is valid and `c_name` is NUL-terminated.
        let id = unsafe {
            self.mj
                .mj_name2id(self.raw.as_ptr(), kind.mj_obj(), c_name.as_ptr())
        };
        usize::try_from(id).map_err(|_| ModelError::UnknownName {
            kind,
            name: name.to_owned(),
        })
    }
}

impl Drop for Model {
    fn drop(&mut self) {
        // SAFETY: the pointer came from mj_loadXML and is freed exactly once, here.
        unsafe { self.mj.mj_deleteModel(self.raw.as_ptr()) }
    }
}

impl fmt::Debug for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Model")
            .field("nq", &self.nq())
            .field("nv", &self.nv())
            .field("nu", &self.nu())
            .field("nbody", &self.count(ObjectKind::Body))
            .field("timestep", &self.timestep())
            .finish()
    }
}

fn load(
    mj: &'static sys::MuJoCo,
    file: &str,
    vfs: Option<&Vfs>,
    origin: &str,
) -> Result<Model, ModelError> {
    let c_file = CString::new(file).map_err(|_| ModelError::InteriorNul {
        what: format!("path {file:?}"),
    })?;
    let mut error = [0 as c_char; ERROR_CAPACITY];
    let vfs_ptr = vfs.map_or(std::ptr::null(), Vfs::as_ptr);
    // SAFETY: `c_file` is NUL-terminated, `vfs_ptr` is null or a live VFS, and `error` has the
    // capacity passed; mj_loadXML catches its own parse/compile errors.
    let raw = unsafe {
        mj.mj_loadXML(
            c_file.as_ptr(),
            vfs_ptr,
            error.as_mut_ptr(),
            ERROR_CAPACITY as i32,
        )
    };
    match NonNull::new(raw) {
        Some(raw) => Ok(Model { raw, mj }),
        None => {
            // SAFETY: MuJoCo NUL-terminates the message within the buffer it was given.
            let message = unsafe { CStr::from_ptr(error.as_ptr()) }.to_string_lossy();
            Err(ModelError::Compile {
                origin: origin.to_owned(),
                message: message.into_owned(),
            })
        }
    }
}

/// MuJoCo sizes are signed; a negative one would be a corrupt model.
pub(crate) fn to_usize(value: impl TryInto<usize>) -> usize {
    value.try_into().unwrap_or(0)
}

/// A weld that ties a mocap body to a body of the model ([`Model::mocap_welds`]).
#[derive(Debug, Clone, PartialEq)]
pub struct MocapWeld {
    /// The weld's name, if it has one.
    pub name: Option<String>,
    /// The mocap body.
    pub mocap: BodyId,
    /// The body the weld holds to it.
    pub held: BodyId,
}

/// The kinds of named object that can be looked up in a [`Model`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ObjectKind {
    /// `<body>`; the world body is id 0.
    Body,
    /// `<joint>` and `<freejoint>`.
    Joint,
    /// `<geom>`.
    Geom,
    /// `<site>`.
    Site,
    /// `<camera>`.
    Camera,
    /// Any element under `<actuator>`.
    Actuator,
    /// Any element under `<sensor>`.
    Sensor,
    /// `<spatial>` and `<fixed>` tendons.
    Tendon,
    /// `<key>`.
    Keyframe,
    /// Any element under `<equality>` (a weld, a connect, a joint or tendon coupling).
    Equality,
}

impl ObjectKind {
    fn mj_obj(self) -> i32 {
        let obj = match self {
            ObjectKind::Body => sys::mjOBJ_BODY,
            ObjectKind::Joint => sys::mjOBJ_JOINT,
            ObjectKind::Geom => sys::mjOBJ_GEOM,
            ObjectKind::Site => sys::mjOBJ_SITE,
            ObjectKind::Camera => sys::mjOBJ_CAMERA,
            ObjectKind::Actuator => sys::mjOBJ_ACTUATOR,
            ObjectKind::Sensor => sys::mjOBJ_SENSOR,
            ObjectKind::Tendon => sys::mjOBJ_TENDON,
            ObjectKind::Keyframe => sys::mjOBJ_KEY,
            ObjectKind::Equality => sys::mjOBJ_EQUALITY,
        };
        obj as i32
    }
}

impl fmt::Display for ObjectKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ObjectKind::Body => "body",
            ObjectKind::Joint => "joint",
            ObjectKind::Geom => "geom",
            ObjectKind::Site => "site",
            ObjectKind::Camera => "camera",
            ObjectKind::Actuator => "actuator",
            ObjectKind::Sensor => "sensor",
            ObjectKind::Tendon => "tendon",
            ObjectKind::Keyframe => "keyframe",
            ObjectKind::Equality => "equality constraint",
        })
    }
}

/// What the typed ids share, so that one check serves them all.
pub(crate) trait TypedId: Copy {
    const KIND: ObjectKind;

    fn parts(self) -> (usize, u64);
}

impl Model {
    /// Whether `id` was resolved in a model with this signature.
    pub(crate) fn owns<I: TypedId>(&self, id: I) -> bool {
        id.parts().1 == self.signature()
    }

    /// The index of `id`, which must have been resolved in a model with this signature.
    #[track_caller]
    pub(crate) fn index_of<I: TypedId>(&self, id: I) -> usize {
        let (index, _) = id.parts();
        assert!(
            self.owns(id),
            "{} id {index} used with a model it was not resolved in",
            I::KIND
        );
        index
    }
}

macro_rules! object_ids {
    ($($(#[$doc:meta])* $id:ident, $kind:ident, $lookup:ident;)*) => {$(
        $(#[$doc])*
        ///
        /// Obtained from the [`Model`] by name; valid for that model and its copies (same
        /// [`Model::signature`]).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub struct $id {
            index: usize,
            signature: u64,
        }

        impl $id {
            /// The object's index in MuJoCo's arrays.
            pub fn index(self) -> usize {
                self.index
            }

            /// The id of object `index` of `model` (`index` below its count of the kind).
            #[allow(dead_code, reason = "made for every kind; some kinds need it")]
            pub(crate) fn at(model: &Model, index: usize) -> Self {
                Self { index, signature: model.signature() }
            }
        }

        impl TypedId for $id {
            const KIND: ObjectKind = ObjectKind::$kind;

            fn parts(self) -> (usize, u64) {
                (self.index, self.signature)
            }
        }

        impl Model {
            #[doc = concat!("Resolves the name of a ", stringify!($lookup), " to its id.")]
            ///
            /// # Errors
            ///
            /// [`ModelError::UnknownName`] when the model has no such object.
            pub fn $lookup(&self, name: &str) -> Result<$id, ModelError> {
                let index = self.id(ObjectKind::$kind, name)?;
                Ok($id { index, signature: self.signature() })
            }
        }
    )*};
}

object_ids! {
    /// A body of a model.
    BodyId, Body, body;
    /// A joint of a model.
    JointId, Joint, joint;
    /// A geom of a model.
    GeomId, Geom, geom;
    /// A site of a model.
    SiteId, Site, site;
    /// A camera of a model.
    CameraId, Camera, camera;
    /// An actuator of a model.
    ActuatorId, Actuator, actuator;
    /// A sensor of a model.
    SensorId, Sensor, sensor;
    /// A tendon of a model.
    TendonId, Tendon, tendon;
    /// A keyframe of a model.
    KeyframeId, Keyframe, keyframe;
}

/// How a joint's degree of freedom resists motion by itself ([`Model::joint_losses`]): MuJoCo's
/// `damping` (force per unit of velocity), `frictionloss` (dry friction, the force it takes to
/// move the joint at all) and `armature` (inertia added to its diagonal of the mass matrix).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JointLosses {
    /// Viscous damping: N·m·s/rad (hinge) or N·s/m (slide).
    pub damping: f64,
    /// Dry friction: N·m (hinge) or N (slide).
    pub frictionloss: f64,
    /// Rotor inertia: kg·m² (hinge) or kg (slide).
    pub armature: f64,
    /// The regularizer of MuJoCo's soft dry-friction constraint on the joint: while the
    /// friction holds (its force below `frictionloss`), its force is
    /// `-(a + friction_damping · v) / friction_regularizer`, `a` the acceleration the joint would
    /// have without it, so that a light link is not held still but made heavier and damped.
    pub friction_regularizer: f64,
    /// The damping of the soft friction constraint's reference acceleration (1/s).
    pub friction_damping: f64,
}

/// A position servo's gains and force limits ([`Model::servo_gains`]): its force is
/// `gain · ctrl − kp · q − kv · q̇` (MuJoCo's `gainprm[0]`, `−biasprm[1]`, `−biasprm[2]`), and
/// the joint feels `gear` times it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoGains {
    /// Force per unit of control.
    pub gain: f64,
    /// Force per unit of joint position.
    pub kp: f64,
    /// Force per unit of joint velocity.
    pub kv: f64,
    /// The transmission's ratio from actuator force to joint (or tendon) force.
    pub gear: f64,
    /// The least and most force it gives, if it is limited (`forcerange`).
    pub force_range: Option<[f64; 2]>,
}
