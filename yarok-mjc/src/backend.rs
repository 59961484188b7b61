//! [`Sim`] and its [`SimBackend`]: the `sim` environment — a compiled composition stepped by
//! MuJoCo.

use std::cell::{Cell, Ref, RefCell, RefMut};
use std::rc::Rc;
use std::sync::Arc;

use yarok_core::BoxError;
use yarok_core::component::{Backend, Environment};
use yarok_core::compose::Composition;
use yarok_core::config::Settings;

use crate::{Data, Model, ModelError, ModelSource, SavedState};

/// The `sim` environment: MuJoCo. Components' `Interface<Sim>` implementations get typed
/// handles through [`SimBind`](crate::SimBind).
#[derive(Debug, Clone, Copy)]
pub struct Sim;

impl Environment for Sim {
    const NAME: &'static str = "sim";
    type Backend = SimBackend;
}

/// The `sim` environment's backend: one [`Model`] and its [`Data`], shared with the components'
/// handles on the platform's thread.
pub struct SimBackend {
    model: Arc<Model>,
    source: ModelSource,
    data: Rc<RefCell<Data>>,
    /// Simulation time after the last step, so that reading it needs no borrow of the data.
    time: Cell<f64>,
    /// The state after binding, which an episode's beginning puts back.
    start: RefCell<Option<SavedState>>,
    #[cfg(feature = "render")]
    renderers: RefCell<Vec<(RendererKey, crate::handles::SharedRenderer)>>,
}

impl std::fmt::Debug for SimBackend {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SimBackend")
            .field("model", &self.model)
            .finish()
    }
}

/// What cameras share a renderer by: image width, height and preset.
#[cfg(feature = "render")]
type RendererKey = (u32, u32, crate::RenderPreset);

impl SimBackend {
    /// Compiles the composition and makes its state, with derived quantities computed.
    ///
    /// # Errors
    ///
    /// [`ModelError`] when MuJoCo rejects the model (naming the component, template and line).
    pub fn new(composition: &Composition) -> Result<Self, ModelError> {
        Self::with_model(
            Arc::new(Model::from_composition(composition)?),
            ModelSource::Compiled,
        )
    }

    pub(crate) fn with_model(model: Arc<Model>, source: ModelSource) -> Result<Self, ModelError> {
        let mut data = Data::new(&model)?;
        data.forward();
        Ok(Self {
            time: Cell::new(data.time()),
            start: RefCell::new(None),
            model,
            source,
            data: Rc::new(RefCell::new(data)),
            #[cfg(feature = "render")]
            renderers: RefCell::new(Vec::new()),
        })
    }

    /// A platform's backend factory (`builder.backend::<Sim>(SimBackend::from_settings)`):
    /// the composition's model shared with the process's other worlds compiled from the same,
    /// or loaded from the cache folder `[platform] model_cache` names, or compiled (see
    /// [`Model::cached`]); its own data.
    ///
    /// # Errors
    ///
    /// As [`SimBackend::new`]; a bad `[platform]` setting.
    pub fn from_settings(composition: &Composition, settings: &Settings) -> Result<Self, BoxError> {
        let folder = settings.platform_settings()?.model_cache.folder();
        let (model, source) = Model::cached(composition, folder.as_deref())?;
        Ok(Self::with_model(model, source)?)
    }

    /// Where the model came from: shared with another world, the cache folder, or compiled.
    pub fn model_source(&self) -> ModelSource {
        self.source
    }

    /// The compiled model.
    pub fn model(&self) -> &Arc<Model> {
        &self.model
    }

    /// The simulation state, for plugins (recorders, viewers). Components' handles borrow it
    /// too: drop this before calling a handle that writes (`actuator.set`).
    pub fn data(&self) -> Ref<'_, Data> {
        self.data.borrow()
    }

    /// The simulation state, writable, for plugins that change it (a viewer's reset); see
    /// [`SimBackend::data`].
    pub fn data_mut(&self) -> RefMut<'_, Data> {
        self.data.borrow_mut()
    }

    pub(crate) fn shared_data(&self) -> Rc<RefCell<Data>> {
        Rc::clone(&self.data)
    }

    /// A renderer of this size, shared by every camera that renders at that size.
    #[cfg(feature = "render")]
    pub(crate) fn renderer(
        &self,
        width: u32,
        height: u32,
        preset: crate::RenderPreset,
    ) -> Result<crate::handles::SharedRenderer, crate::RenderError> {
        let key = (width, height, preset);
        let mut renderers = self.renderers.borrow_mut();
        if let Some((_, renderer)) = renderers.iter().find(|(made, _)| *made == key) {
            return Ok(Rc::clone(renderer));
        }
        let renderer = Rc::new(RefCell::new(
            crate::Renderer::builder()
                .size(width, height)
                .preset(preset)
                .build(&self.model)?,
        ));
        renderers.push((key, Rc::clone(&renderer)));
        Ok(renderer)
    }
}

impl Backend for SimBackend {
    fn step(&self) -> Result<f64, BoxError> {
        let mut data = self.data.try_borrow_mut().map_err(|_| {
            "the simulation data is still borrowed when the platform steps: a plugin keeps a \
             `data()` borrow past its step"
        })?;
        data.step();
        let time = data.time();
        self.time.set(time);
        Ok(time)
    }

    fn time(&self) -> f64 {
        self.time.get()
    }

    fn timestep(&self) -> f64 {
        self.model.timestep()
    }

    fn paced(&self) -> bool {
        false
    }

    fn remember_start(&self) {
        *self.start.borrow_mut() = Some(self.data.borrow().save_state());
    }

    fn restart(&self) -> Result<(), BoxError> {
        let start = self.start.borrow();
        let start = start
            .as_ref()
            .ok_or("the world has not started: there is no start state yet")?;
        let mut data = self.data.try_borrow_mut().map_err(
            |_| "the simulation data is borrowed: a plugin keeps a `data()` borrow past its step",
        )?;
        data.restore_state(start);
        Ok(())
    }
}
