//! [`DeclaredWorld`]: the composed world as its templates placed it, for components' `mock`
//! interfaces — the model compiled when first asked for, at its initial state, with no physics —
//! and [`MockBind`], what a mock drive reads of it: joints it may set (kinematics only),
//! bodies' and sites' poses, and cameras that render it.

use std::cell::OnceCell;
use std::path::PathBuf;

use yarok_core::BoxError;
use yarok_core::component::{Bind, BindError, Mock, NameKind};
use yarok_core::compose::Composition;
use yarok_core::config::Settings;

use crate::handles::{Body, Joint, Site};
use crate::{Model, SimBackend};

/// The composed world as declared, for `mock`: attached to the mock backend
/// ([`MockBackend::with_world`](yarok_core::component::MockBackend::with_world)), its model
/// compiled (or loaded from the model cache) when a mock drive first asks for it.
pub struct DeclaredWorld {
    composition: Composition,
    cache_folder: Option<PathBuf>,
    sim: OnceCell<Result<SimBackend, String>>,
}

impl std::fmt::Debug for DeclaredWorld {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DeclaredWorld")
            .field("compiled", &self.sim.get().is_some())
            .finish()
    }
}

impl DeclaredWorld {
    /// The declared world of `composition`, its model cached where `[platform] model_cache`
    /// says.
    ///
    /// # Errors
    ///
    /// A bad `[platform]` setting.
    pub fn new(composition: &Composition, settings: &Settings) -> Result<Self, BoxError> {
        Ok(Self {
            composition: composition.clone(),
            cache_folder: settings.platform_settings()?.model_cache.folder(),
            sim: OnceCell::new(),
        })
    }

    /// The world's model and state: compiled at the first call, at its initial state.
    ///
    /// # Errors
    ///
    /// MuJoCo's refusal of the model, naming the component, template and line.
    pub fn sim(&self) -> Result<&SimBackend, String> {
        self.sim
            .get_or_init(|| {
                let (model, source) =
                    Model::cached(&self.composition, self.cache_folder.as_deref())
                        .map_err(|e| e.to_string())?;
                SimBackend::with_model(model, source).map_err(|e| e.to_string())
            })
            .as_ref()
            .map_err(Clone::clone)
    }
}

/// What a component's `mock` interface sees of the world as declared ([`DeclaredWorld`]): its
/// joints, bodies, sites and cameras by the component's own names, as the templates placed them.
/// Nothing moves by itself there: a mock drive that sets a joint moves what hangs from it
/// (kinematics only), so that its cameras see it.
pub trait MockBind {
    /// The declared world's model and state.
    ///
    /// # Errors
    ///
    /// When the platform attached none, or its model does not compile.
    fn declared(&self) -> Result<&SimBackend, BindError>;

    /// A joint of the declared world.
    ///
    /// # Errors
    ///
    /// As [`MockBind::declared`]; a name the template lacks.
    fn declared_joint(&self, local: &str) -> Result<Joint, BindError>;

    /// A body of the declared world.
    ///
    /// # Errors
    ///
    /// As [`MockBind::declared_joint`].
    fn declared_body(&self, local: &str) -> Result<Body, BindError>;

    /// A site of the declared world.
    ///
    /// # Errors
    ///
    /// As [`MockBind::declared_joint`].
    fn declared_site(&self, local: &str) -> Result<Site, BindError>;

    /// A camera of the declared world, rendering it as it stands.
    ///
    /// # Errors
    ///
    /// As [`MockBind::declared_joint`]; when no renderer can be made.
    #[cfg(feature = "render")]
    fn declared_camera_with(
        &self,
        local: &str,
        width: u32,
        height: u32,
        preset: crate::RenderPreset,
    ) -> Result<crate::Camera, BindError>;
}

impl MockBind for Bind<Mock> {
    fn declared(&self) -> Result<&SimBackend, BindError> {
        let world = self.backend().world::<DeclaredWorld>().ok_or_else(|| {
            self.error("this platform's mock has no declared world attached (yarok's has)")
        })?;
        world.sim().map_err(|e| self.error(e))
    }

    fn declared_joint(&self, local: &str) -> Result<Joint, BindError> {
        let name = self.name(NameKind::Joint, local)?;
        let sim = self.declared()?;
        let id = sim.model().joint(name).map_err(|e| self.error(e))?;
        Ok(Joint {
            data: sim.shared_data(),
            id,
        })
    }

    fn declared_body(&self, local: &str) -> Result<Body, BindError> {
        let name = self.name(NameKind::Body, local)?;
        let sim = self.declared()?;
        let id = sim.model().body(name).map_err(|e| self.error(e))?;
        Ok(Body {
            data: sim.shared_data(),
            id,
        })
    }

    fn declared_site(&self, local: &str) -> Result<Site, BindError> {
        let name = self.name(NameKind::Site, local)?;
        let sim = self.declared()?;
        let id = sim.model().site(name).map_err(|e| self.error(e))?;
        Ok(Site {
            data: sim.shared_data(),
            id,
        })
    }

    #[cfg(feature = "render")]
    fn declared_camera_with(
        &self,
        local: &str,
        width: u32,
        height: u32,
        preset: crate::RenderPreset,
    ) -> Result<crate::Camera, BindError> {
        let name = self.name(NameKind::Camera, local)?;
        let sim = self.declared()?;
        let id = sim.model().camera(name).map_err(|e| self.error(e))?;
        let renderer = sim
            .renderer(width, height, preset)
            .map_err(|e| self.error(e))?;
        Ok(crate::Camera::new(sim.shared_data(), renderer, id))
    }
}
