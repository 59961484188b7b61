//! Typed handles on the simulation: what `Interface<Sim>` implementations hold. Each carries the
//! shared simulation state inside and borrows it only within its own methods, so no component
//! code touches a `RefCell` or holds a borrow across an `.await`.

use std::cell::RefCell;
use std::rc::Rc;

use yarok_core::component::{Bind, BindError, NameKind};

use crate::{ActuatorId, BodyId, ContactPoint, Data, GeomId, JointId, Pose, SensorId, Sim, SiteId};

/// A renderer shared by the cameras that render at its size.
#[cfg(feature = "render")]
pub(crate) type SharedRenderer = Rc<RefCell<crate::Renderer>>;

macro_rules! handle {
    ($(#[$doc:meta])* $name:ident($id:ty)) => {
        $(#[$doc])*
        #[derive(Clone)]
        pub struct $name {
            pub(crate) data: Rc<RefCell<Data>>,
            pub(crate) id: $id,
        }

        impl $name {
            /// The object's id in the model.
            pub fn id(&self) -> $id {
                self.id
            }
        }

        impl std::fmt::Debug for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.debug_tuple(stringify!($name)).field(&self.id).finish()
            }
        }
    };
}

handle! {
    /// An actuator: its control input.
    Actuator(ActuatorId)
}

impl Actuator {
    /// Sets the control input (a position servo's target, a motor's torque).
    pub fn set(&self, value: f64) {
        self.data.borrow_mut().set_ctrl(self.id, value);
    }

    /// The control input.
    pub fn get(&self) -> f64 {
        self.data.borrow().ctrl()[self.id.index()]
    }

    /// Its gains if it is a position servo on a joint (see [`Model::servo_gains`]).
    ///
    /// [`Model::servo_gains`]: crate::Model::servo_gains
    pub fn servo_gains(&self) -> Option<crate::ServoGains> {
        self.data.borrow().model().servo_gains(self.id)
    }

    /// The range its control is clamped to, if it is limited (see [`Model::ctrl_range`]).
    ///
    /// [`Model::ctrl_range`]: crate::Model::ctrl_range
    pub fn ctrl_range(&self) -> Option<[f64; 2]> {
        self.data.borrow().model().ctrl_range(self.id)
    }

    /// Its length and the rate it changes at (see [`Data::actuator_length`]).
    ///
    /// [`Data::actuator_length`]: crate::Data::actuator_length
    pub fn length(&self) -> (f64, f64) {
        self.data.borrow().actuator_length(self.id)
    }
}

handle! {
    /// A sensor: its reading after the last step.
    Sensor(SensorId)
}

impl Sensor {
    /// The reading's first (for most sensors, only) number.
    pub fn value(&self) -> f64 {
        self.data.borrow().sensor(self.id)[0]
    }

    /// Every number of the reading (3 for a force sensor, 4 for a quaternion, …).
    pub fn values(&self) -> Vec<f64> {
        self.data.borrow().sensor(self.id).to_vec()
    }
}

handle! {
    /// A joint: its position and velocity.
    Joint(JointId)
}

impl Joint {
    /// The position of a hinge (radians) or slide (metres) joint: its first coordinate.
    pub fn position(&self) -> f64 {
        self.data.borrow().qpos(self.id)[0]
    }

    /// The velocity of a hinge or slide joint: its first degree of freedom.
    pub fn velocity(&self) -> f64 {
        self.data.borrow().qvel(self.id)[0]
    }

    /// Puts a hinge or slide joint at `position` and at rest, and recomputes what follows from
    /// it (body poses, sensors), as at the start of a run.
    pub fn set_position(&self, position: f64) {
        let mut data = self.data.borrow_mut();
        data.qpos_mut(self.id)[0] = position;
        data.qvel_mut(self.id)[0] = 0.0;
        data.forward();
    }

    /// Puts a free joint's body at `position` (metres, world frame) with `orientation` (a unit
    /// quaternion, w first) and at rest, and recomputes what follows from it, as at the start
    /// of a run.
    ///
    /// # Errors
    ///
    /// When the joint is not a free joint, or the quaternion is not of unit length.
    pub fn set_free_pose(&self, position: [f64; 3], orientation: [f64; 4]) -> Result<(), String> {
        let norm = orientation.iter().map(|q| q * q).sum::<f64>().sqrt();
        if !((1.0 - 1e-6)..=(1.0 + 1e-6)).contains(&norm) {
            return Err(format!(
                "the orientation {orientation:?} is not a unit quaternion (its length is {norm})"
            ));
        }
        let mut data = self.data.borrow_mut();
        let qpos = data.qpos_mut(self.id);
        if qpos.len() != 7 {
            return Err("only a free joint's body can be placed".into());
        }
        qpos[..3].copy_from_slice(&position);
        qpos[3..].copy_from_slice(&orientation);
        data.qvel_mut(self.id).fill(0.0);
        data.forward();
        Ok(())
    }

    /// What the constraints of the last step (contacts, equality constraints, limits, dry
    /// friction) put on the joint's first degree of freedom, by source, the strongest first
    /// (see [`Data::constraint_forces_on`]).
    pub fn constraint_forces(&self) -> Vec<crate::ConstraintForce> {
        let data = self.data.borrow();
        data.constraint_forces_on(data.dof(self.id))
    }

    /// The joint-space inertia the joint sees (see [`Data::dof_inertia`]).
    pub fn inertia(&self) -> f64 {
        self.data.borrow().dof_inertia(self.id)
    }

    /// The force gravity and the motion's own inertia put on the joint that the model does not
    /// compensate (see [`Data::dof_bias_force`]).
    pub fn bias_force(&self) -> f64 {
        self.data.borrow().dof_bias_force(self.id)
    }

    /// The generalised force each of `joints` (hinge or slide joints) needs to give the
    /// accelerations `accelerations` (one each; every other degree of freedom unaccelerated),
    /// through the whole joint-space inertia matrix, couplings included (see
    /// [`Data::inertia_times`]). As of the last step. Empty when `joints` is.
    ///
    /// # Panics
    ///
    /// When the slices' lengths differ.
    pub fn inertial_forces(joints: &[Joint], accelerations: &[f64]) -> Vec<f64> {
        assert_eq!(
            joints.len(),
            accelerations.len(),
            "one acceleration per joint"
        );
        let Some(first) = joints.first() else {
            return Vec::new();
        };
        let data = first.data.borrow();
        let nv = data.model().nv();
        let mut vector = vec![0.0; nv];
        for (joint, acceleration) in joints.iter().zip(accelerations) {
            vector[data.dof(joint.id)] = *acceleration;
        }
        let mut forces = vec![0.0; nv];
        data.inertia_times(&vector, &mut forces);
        joints
            .iter()
            .map(|joint| forces[data.dof(joint.id)])
            .collect()
    }

    /// Every position coordinate (7 for a free joint, 4 for a ball).
    pub fn qpos(&self) -> Vec<f64> {
        self.data.borrow().qpos(self.id).to_vec()
    }

    /// Every velocity (6 for a free joint, 3 for a ball).
    pub fn qvel(&self) -> Vec<f64> {
        self.data.borrow().qvel(self.id).to_vec()
    }
}

handle! {
    /// A body: its pose in the world.
    Body(BodyId)
}

impl Body {
    /// The pose in world coordinates after the last step (see [`Data::body_pose`]).
    pub fn pose(&self) -> Pose {
        self.data.borrow().body_pose(self.id)
    }

    /// The gap between this body's surface and `other`'s after the last step (see
    /// [`Data::body_gap`]): the least distance between their colliding geoms, up to 1 m;
    /// `None` when either has no colliding geom.
    pub fn gap_to(&self, other: &Body) -> Option<f64> {
        self.data.borrow_mut().body_gap(self.id, other.id)
    }
}

handle! {
    /// A site: its pose in the world (a tool centre point, a mounting point).
    Site(SiteId)
}

impl Site {
    /// The pose in world coordinates after the last step (see [`Data::site_pose`]).
    pub fn pose(&self) -> Pose {
        self.data.borrow().site_pose(self.id)
    }

    /// The generalised force on each of `joints` of a force `force` (world coordinates) at
    /// `point` (world coordinates) fixed to the site's body: reversed, what each joint must
    /// give to hold it. As of the last step (see [`Data::point_jacobian`]).
    pub fn forces_on(&self, joints: &[Joint], point: [f64; 3], force: [f64; 3]) -> Vec<f64> {
        let data = self.data.borrow();
        let jacobian = data.point_jacobian(data.model().site_body(self.id), point);
        joints
            .iter()
            .map(|joint| {
                let column = jacobian[data.dof(joint.id)];
                (0..3).map(|axis| column[axis] * force[axis]).sum()
            })
            .collect()
    }
}

handle! {
    /// A geom: the contacts it is in.
    Geom(GeomId)
}

impl Geom {
    /// The contacts this geom is in after the last step, each with the other geom second (its
    /// normal pointing from this geom to the other).
    pub fn contacts(&self) -> Vec<ContactPoint> {
        self.data
            .borrow()
            .contacts_of(self.id)
            .into_iter()
            .map(|contact| match contact.geoms {
                [other, second] if second == self.id && other != self.id => ContactPoint {
                    geoms: [second, other],
                    normal: contact.normal.map(|n| -n),
                    ..contact
                },
                _ => contact,
            })
            .collect()
    }
}

/// A camera with its renderer: colour and depth images of the current state.
#[cfg(feature = "render")]
#[derive(Clone)]
pub struct Camera {
    data: Rc<RefCell<Data>>,
    renderer: SharedRenderer,
    id: crate::CameraId,
    visible: [bool; 6],
    reach: Option<f64>,
    touching: Option<GeomId>,
}

#[cfg(feature = "render")]
impl std::fmt::Debug for Camera {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("Camera").field(&self.id).finish()
    }
}

#[cfg(feature = "render")]
impl Camera {
    /// A camera `id` of the state `data`, drawn by `renderer`, seeing every geom group.
    pub(crate) fn new(
        data: Rc<RefCell<Data>>,
        renderer: SharedRenderer,
        id: crate::CameraId,
    ) -> Self {
        Self {
            data,
            renderer,
            id,
            visible: [true; 6],
            reach: None,
            touching: None,
        }
    }

    /// The same camera, not drawing geoms of the `hidden` groups (0–5, MJCF's `group`).
    #[must_use]
    pub fn hiding_groups(mut self, hidden: &[usize]) -> Self {
        for &group in hidden {
            if let Some(visible) = self.visible.get_mut(group) {
                *visible = false;
            }
        }
        self
    }

    /// The same camera, drawing only geoms that may come within `reach` metres of it (see
    /// [`Renderer::set_reach`](crate::Renderer::set_reach)).
    #[must_use]
    pub fn within(mut self, reach: f64) -> Self {
        self.reach = Some(reach);
        self
    }

    /// The same camera, drawing only the geoms that could touch `geom` (see
    /// [`Renderer::set_touching`](crate::Renderer::set_touching)): a tactile sensor's camera
    /// sees only what can press into its gel.
    #[must_use]
    pub fn touching(mut self, geom: &Geom) -> Self {
        self.touching = Some(geom.id);
        self
    }

    /// The renderer, set to this camera's visible groups, reach and touched geom.
    fn renderer(&self) -> std::cell::RefMut<'_, crate::Renderer> {
        let mut renderer = self.renderer.borrow_mut();
        renderer.set_visible_groups(self.visible);
        renderer.set_reach(self.reach);
        renderer.set_touching(self.touching);
        renderer
    }

    /// The current colour image, top row first.
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn rgb(&self) -> Result<image::RgbImage, crate::RenderError> {
        self.renderer()
            .render_rgb(&mut self.data.borrow_mut(), self.id)
    }

    /// The current depth image in metres (planar distance along the camera axis).
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn depth(&self) -> Result<crate::DepthImage, crate::RenderError> {
        self.renderer()
            .render_depth(&mut self.data.borrow_mut(), self.id)
    }

    /// The current colour and depth images from one draw.
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn rgbd(&self) -> Result<(image::RgbImage, crate::DepthImage), crate::RenderError> {
        self.renderer().render(&mut self.data.borrow_mut(), self.id)
    }

    /// The current depth image into `depth`, reusing its memory (see
    /// [`Renderer::render_depth_into`](crate::Renderer::render_depth_into)).
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn depth_into(&self, depth: &mut crate::DepthImage) -> Result<(), crate::RenderError> {
        self.renderer()
            .render_depth_into(&mut self.data.borrow_mut(), self.id, depth)
    }
}

/// Typed handles on what a component's template names, for its `Interface<Sim>`.
///
/// # Examples
///
/// ```
/// use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces};
/// use yarok_mjc::{Actuator, Sensor, Sim, SimBind};
///
/// #[derive(Clone)]
/// struct Hinge { motor: Actuator, angle: Sensor }
///
/// impl Component for Hinge {
///     fn declaration() -> Declaration {
///         Declaration::new("hinge").template(r#"<mujoco>
///             <worldbody><body name="arm"><joint name="j"/><geom size="0.1"/></body></worldbody>
///             <actuator><position name="motor" joint="j" kp="10" dampratio="1"/></actuator>
///             <sensor><jointpos name="angle" joint="j"/></sensor>
///         </mujoco>"#)
///     }
///     fn interfaces(interfaces: &mut Interfaces<Self>) {
///         interfaces.add::<Sim>();
///     }
/// }
///
/// impl Interface<Sim> for Hinge {
///     async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
///         Ok(Hinge { motor: bind.actuator("motor")?, angle: bind.sensor("angle")? })
///     }
/// }
///
/// yarok_core::runtime::Platform::builder()
///     .world::<Hinge>()
///     .backend::<Sim>(yarok_mjc::SimBackend::from_settings)
///     .behaviour(|pl| async move {
///         let hinge: Hinge = pl.get("/")?;
///         hinge.motor.set(0.5);
///         pl.wait_seconds(3.0).await?;
///         assert!((hinge.angle.value() - 0.5).abs() < 0.05);
///         Ok(())
///     })
///     .run()?;
/// # Ok::<(), yarok_core::runtime::RuntimeError>(())
/// ```
pub trait SimBind {
    /// The actuator the component's template names `local`.
    ///
    /// # Errors
    ///
    /// [`BindError`] when the template or the model has no such actuator.
    fn actuator(&self, local: &str) -> Result<Actuator, BindError>;

    /// The one actuator that drives `joint` (its transmission is the joint), named or not:
    /// how an arm finds its actuators in files that leave them unnamed, as gym-aloha's ALOHA
    /// does.
    ///
    /// # Errors
    ///
    /// [`BindError`] when no actuator drives the joint, or more than one does (naming them).
    fn actuator_driving(&self, joint: &Joint) -> Result<Actuator, BindError>;

    /// The sensor the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::actuator`].
    fn sensor(&self, local: &str) -> Result<Sensor, BindError>;

    /// The joint the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::actuator`].
    fn joint(&self, local: &str) -> Result<Joint, BindError>;

    /// The body the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::actuator`].
    fn body(&self, local: &str) -> Result<Body, BindError>;

    /// The site the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::actuator`].
    fn site(&self, local: &str) -> Result<Site, BindError>;

    /// The geom the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::actuator`].
    fn geom(&self, local: &str) -> Result<Geom, BindError>;

    /// The camera the template names `local`, rendering `width` × `height` pixels (cameras of
    /// one size share a renderer).
    ///
    /// # Errors
    ///
    /// As [`SimBind::actuator`], or when no renderer can be made.
    #[cfg(feature = "render")]
    fn camera(&self, local: &str, width: u32, height: u32) -> Result<Camera, BindError> {
        self.camera_with(local, width, height, crate::RenderPreset::Quality)
    }

    /// [`SimBind::camera`] rendering with `preset` (cameras of one size and preset share a
    /// renderer): [`RenderPreset::Fast`](crate::RenderPreset::Fast) for a camera whose images
    /// no one looks at closely, [`RenderPreset::Depth`](crate::RenderPreset::Depth) for one
    /// whose depth alone is used.
    ///
    /// # Errors
    ///
    /// As [`SimBind::camera`].
    #[cfg(feature = "render")]
    fn camera_with(
        &self,
        local: &str,
        width: u32,
        height: u32,
        preset: crate::RenderPreset,
    ) -> Result<Camera, BindError>;
}

macro_rules! lookups {
    ($($method:ident: $kind:ident => $lookup:ident -> $handle:ident;)*) => {$(
        fn $method(&self, local: &str) -> Result<$handle, BindError> {
            let name = self.name(NameKind::$kind, local)?;
            let backend = self.backend();
            let id = backend.model().$lookup(name).map_err(|e| self.error(e))?;
            Ok($handle { data: backend.shared_data(), id })
        }
    )*};
}

impl SimBind for Bind<Sim> {
    lookups! {
        actuator: Actuator => actuator -> Actuator;
        sensor: Sensor => sensor -> Sensor;
        joint: Joint => joint -> Joint;
        body: Body => body -> Body;
        site: Site => site -> Site;
        geom: Geom => geom -> Geom;
    }

    fn actuator_driving(&self, joint: &Joint) -> Result<Actuator, BindError> {
        let backend = self.backend();
        let model = backend.model();
        let driving: Vec<ActuatorId> = model
            .actuators()
            .filter(|&actuator| model.actuator_joint(actuator) == Some(joint.id()))
            .collect();
        let joint_name = model
            .joint_name(joint.id())
            .unwrap_or_else(|| format!("#{}", joint.id().index()));
        match driving[..] {
            [id] => Ok(Actuator {
                data: backend.shared_data(),
                id,
            }),
            [] => Err(self.error(format!(
                "no actuator drives joint {joint_name:?}: the file declares none on it"
            ))),
            _ => {
                let named: Vec<String> = driving
                    .iter()
                    .map(|&id| {
                        model
                            .actuator_name(id)
                            .unwrap_or_else(|| format!("#{} (unnamed)", id.index()))
                    })
                    .collect();
                Err(self.error(format!(
                    "{} actuators drive joint {joint_name:?} ({}): name the one to use",
                    driving.len(),
                    named.join(", ")
                )))
            }
        }
    }

    #[cfg(feature = "render")]
    fn camera_with(
        &self,
        local: &str,
        width: u32,
        height: u32,
        preset: crate::RenderPreset,
    ) -> Result<Camera, BindError> {
        let name = self.name(NameKind::Camera, local)?;
        let backend = self.backend();
        let id = backend.model().camera(name).map_err(|e| self.error(e))?;
        let renderer = backend
            .renderer(width, height, preset)
            .map_err(|e| self.error(e))?;
        Ok(Camera::new(backend.shared_data(), renderer, id))
    }
}
