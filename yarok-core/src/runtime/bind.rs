//! [`Bind`]: what a component sees while it makes its handle at start-up.

use std::any::Any;
use std::collections::HashMap;

use super::{Backend, BoxError, RuntimeError};
use crate::compose::{Component, Config, Instance, NameKind};

/// A per-tick step an interface registered.
pub(crate) type Step = Box<dyn FnMut() -> Result<(), BoxError>>;

/// A bound component's handle; `None` for components with no run-time interface.
pub(crate) type Handle = Option<Box<dyn Any>>;

/// The context in which a component makes its handle: its environment, config, names, the
/// backend, and its already bound children.
pub struct Bind<'a> {
    pub(crate) environment: &'a str,
    pub(crate) instance: &'a Instance,
    pub(crate) interface: &'a Config,
    pub(crate) backend: &'a dyn Backend,
    pub(crate) steps: &'a mut Vec<(String, Step)>,
    pub(crate) handles: &'a HashMap<String, Handle>,
}

impl Bind<'_> {
    /// The selected environment: `"sim"`, `"real"`, `"mock"`, …
    pub fn environment(&self) -> &str {
        self.environment
    }

    /// The component's path.
    pub fn path(&self) -> &str {
        &self.instance.path
    }

    /// The component's config (defaults, tag attributes and run settings applied).
    pub fn config(&self) -> &Config {
        &self.instance.config
    }

    /// The interface settings for this component (`[interfaces."/path"]`).
    pub fn interface_config(&self) -> &Config {
        self.interface
    }

    /// The composed-model name of something the component's template calls `local`.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Bind`] when the template defines no such name.
    pub fn name(&self, kind: NameKind, local: &str) -> Result<&str, RuntimeError> {
        self.instance
            .names
            .get(kind, local)
            .ok_or_else(|| self.error(format!("its template has no {kind} named {local:?}")))
    }

    /// The backend, as its concrete type.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Bind`] when the running backend is another type.
    pub fn backend<B: Backend>(&self) -> Result<&B, RuntimeError> {
        self.backend.as_any().downcast_ref::<B>().ok_or_else(|| {
            self.error(format!(
                "its {} interface needs a {} backend",
                self.environment,
                std::any::type_name::<B>()
            ))
        })
    }

    /// Registers work to do after every backend step (children's before their parents').
    pub fn on_step(&mut self, step: impl FnMut() -> Result<(), BoxError> + 'static) {
        self.steps
            .push((self.instance.path.clone(), Box::new(step)));
    }

    /// The handle of a child component, by name.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::NoComponent`] or [`RuntimeError::WrongType`].
    pub fn child<C: Component + Clone>(&self, name: &str) -> Result<C, RuntimeError> {
        let path = if self.instance.path == "/" {
            format!("/{name}")
        } else {
            format!("{}/{name}", self.instance.path)
        };
        super::platform::handle::<C>(self.handles, &path)
    }

    /// The error for a component that has no interface for the selected environment.
    pub fn no_interface(&self) -> RuntimeError {
        RuntimeError::NoInterface {
            component: self.instance.path.clone(),
            environment: self.environment.to_owned(),
        }
    }

    /// A binding error naming this component.
    pub fn error(&self, message: impl Into<String>) -> RuntimeError {
        RuntimeError::Bind {
            component: self.instance.path.clone(),
            message: message.into(),
        }
    }
}

impl std::fmt::Debug for Bind<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Bind")
            .field("environment", &self.environment)
            .field("path", &self.instance.path)
            .finish()
    }
}
