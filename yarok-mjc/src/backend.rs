//! [`SimBackend`]: the `sim` environment — a compiled composition stepped by MuJoCo.

use std::any::Any;
use std::cell::RefCell;
use std::rc::Rc;
use std::sync::Arc;

use yarok_core::compose::{Composition, NameKind};
use yarok_core::config::Settings;
use yarok_core::runtime::{Backend, Bind, RuntimeError};

use crate::{ActuatorId, BodyId, CameraId, Data, JointId, Model, ModelError, SensorId, SiteId};

/// The `sim` environment's backend: one [`Model`] and its [`Data`], shared with the components'
/// sim interfaces on the platform's thread.
pub struct SimBackend {
    model: Arc<Model>,
    data: Rc<RefCell<Data>>,
    /// Simulation time after the last step, so that reading it needs no borrow of the data.
    time: f64,
    #[cfg(feature = "render")]
    renderers: RefCell<Vec<((u32, u32), SharedRenderer)>>,
}

/// A renderer shared by the cameras that render at its size.
#[cfg(feature = "render")]
pub type SharedRenderer = Rc<RefCell<crate::Renderer>>;

impl std::fmt::Debug for SimBackend {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SimBackend")
            .field("model", &self.model)
            .finish()
    }
}

impl SimBackend {
    /// Compiles the composition and makes its state, with derived quantities computed.
    ///
    /// # Errors
    ///
    /// [`ModelError`] when MuJoCo rejects the model.
    pub fn new(composition: &Composition) -> Result<Self, ModelError> {
        let model = Arc::new(Model::from_composition(composition)?);
        let mut data = Data::new(&model)?;
        data.forward();
        Ok(Self {
            time: data.time(),
            model,
            data: Rc::new(RefCell::new(data)),
            #[cfg(feature = "render")]
            renderers: RefCell::new(Vec::new()),
        })
    }

    /// A platform [`backend`](yarok_core::runtime::PlatformBuilder::backend) factory.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Backend`] with MuJoCo's message when the model does not compile.
    pub fn from_settings(
        composition: &Composition,
        _: &Settings,
    ) -> Result<Box<dyn Backend>, RuntimeError> {
        Self::new(composition)
            .map(|b| Box::new(b) as Box<dyn Backend>)
            .map_err(|e| RuntimeError::Backend(e.to_string()))
    }

    /// The compiled model.
    pub fn model(&self) -> &Arc<Model> {
        &self.model
    }

    /// The simulation state, shared with the interfaces.
    pub fn data(&self) -> Rc<RefCell<Data>> {
        Rc::clone(&self.data)
    }

    /// A renderer of this size, shared by every camera that renders at that size.
    ///
    /// # Errors
    ///
    /// As [`RendererBuilder::build`](crate::RendererBuilder::build).
    #[cfg(feature = "render")]
    pub fn renderer(
        &self,
        width: u32,
        height: u32,
    ) -> Result<Rc<RefCell<crate::Renderer>>, crate::RenderError> {
        let mut renderers = self.renderers.borrow_mut();
        if let Some((_, renderer)) = renderers.iter().find(|(size, _)| *size == (width, height)) {
            return Ok(Rc::clone(renderer));
        }
        let renderer = Rc::new(RefCell::new(
            crate::Renderer::builder()
                .size(width, height)
                .build(&self.model)?,
        ));
        renderers.push(((width, height), Rc::clone(&renderer)));
        Ok(renderer)
    }
}

impl Backend for SimBackend {
    fn step(&mut self) -> Result<(), RuntimeError> {
        let mut data = self.data.try_borrow_mut().map_err(|_| {
            RuntimeError::Backend(
                "the simulation data is still borrowed when the platform steps: a behaviour or \
                 component keeps a `borrow()`/`borrow_mut()` of it across an `.await`; drop the \
                 borrow before awaiting"
                    .into(),
            )
        })?;
        data.step();
        self.time = data.time();
        Ok(())
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn timestep(&self) -> f64 {
        self.model.timestep()
    }

    fn paced(&self) -> bool {
        false
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// What a component's sim interface needs at bind time: the backend, and its local names
/// resolved to typed ids once.
pub trait SimBind {
    /// The sim backend.
    ///
    /// # Errors
    ///
    /// When the running backend is not a [`SimBackend`].
    fn sim(&self) -> Result<&SimBackend, RuntimeError>;

    /// The id of a joint the component's template names `local`.
    ///
    /// # Errors
    ///
    /// When the template or the model has no such joint.
    fn joint_id(&self, local: &str) -> Result<JointId, RuntimeError>;

    /// The id of an actuator the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::joint_id`].
    fn actuator_id(&self, local: &str) -> Result<ActuatorId, RuntimeError>;

    /// The id of a sensor the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::joint_id`].
    fn sensor_id(&self, local: &str) -> Result<SensorId, RuntimeError>;

    /// The id of a camera the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::joint_id`].
    fn camera_id(&self, local: &str) -> Result<CameraId, RuntimeError>;

    /// The id of a body the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::joint_id`].
    fn body_id(&self, local: &str) -> Result<BodyId, RuntimeError>;

    /// The id of a site the template names `local`.
    ///
    /// # Errors
    ///
    /// As [`SimBind::joint_id`].
    fn site_id(&self, local: &str) -> Result<SiteId, RuntimeError>;
}

macro_rules! lookups {
    ($($method:ident: $kind:ident => $lookup:ident -> $id:ty;)*) => {$(
        fn $method(&self, local: &str) -> Result<$id, RuntimeError> {
            let name = self.name(NameKind::$kind, local)?;
            self.sim()?.model().$lookup(name).map_err(|e| self.error(e.to_string()))
        }
    )*};
}

impl SimBind for Bind<'_> {
    fn sim(&self) -> Result<&SimBackend, RuntimeError> {
        self.backend::<SimBackend>()
    }

    lookups! {
        joint_id: Joint => joint -> JointId;
        actuator_id: Actuator => actuator -> ActuatorId;
        sensor_id: Sensor => sensor -> SensorId;
        camera_id: Camera => camera -> CameraId;
        body_id: Body => body -> BodyId;
        site_id: Site => site -> SiteId;
    }
}
