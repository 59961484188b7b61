//! The bound components' handles, by path.

use std::any::Any;
use std::collections::HashMap;

use super::ComponentType;
use crate::suggest::did_you_mean_or_list;

/// A component handle could not be had.
#[derive(Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum HandleError {
    /// No component has this path.
    #[error("no component at {path}{hint}")]
    NoComponent {
        /// The path asked for.
        path: String,
        /// A "did you mean" suggestion, or nothing.
        hint: String,
    },
    /// A component name matches several paths.
    #[error("`{name}` names several components ({paths}); use a path")]
    Ambiguous {
        /// The name asked for.
        name: String,
        /// The paths it matches.
        paths: String,
    },
    /// The component at a path is another type than asked for.
    #[error("{path} is a {found}, not a {expected}")]
    WrongType {
        /// The path asked for.
        path: String,
        /// The type asked for.
        expected: &'static str,
        /// The component's type.
        found: &'static str,
    },
    /// The component has no run-time interface (a world, a prop), or is not bound yet.
    #[error("{path} has no run-time handle (a world or a prop, or not bound yet)")]
    NoHandle {
        /// The component's path.
        path: String,
    },
}

crate::debug_as_report!(HandleError);

/// Every component of the world with its handle once bound.
#[derive(Default)]
pub(crate) struct Handles {
    entries: HashMap<String, (ComponentType, Option<Box<dyn Any>>)>,
}

impl Handles {
    pub(crate) fn new(components: impl IntoIterator<Item = (String, ComponentType)>) -> Self {
        Self {
            entries: components
                .into_iter()
                .map(|(path, component)| (path, (component, None)))
                .collect(),
        }
    }

    pub(crate) fn insert(&mut self, path: &str, handle: Box<dyn Any>) {
        if let Some(entry) = self.entries.get_mut(path) {
            entry.1 = Some(handle);
        }
    }

    /// The handle at `path` (`/arm`), or of the one component named `path` when it has no `/`.
    pub(crate) fn get<C: Clone + 'static>(&self, path: &str) -> Result<C, HandleError> {
        let path = self.resolve(path)?;
        let Some((component, handle)) = self.entries.get(&path) else {
            return Err(HandleError::NoComponent {
                hint: did_you_mean_or_list(&path, self.entries.keys().map(String::as_str)),
                path,
            });
        };
        if component.type_id() != std::any::TypeId::of::<C>() {
            return Err(HandleError::WrongType {
                path,
                expected: std::any::type_name::<C>(),
                found: component.type_name(),
            });
        }
        handle
            .as_ref()
            .and_then(|handle| handle.downcast_ref::<C>())
            .cloned()
            .ok_or(HandleError::NoHandle { path })
    }

    fn resolve(&self, path: &str) -> Result<String, HandleError> {
        if path.starts_with('/') {
            return Ok(path.to_owned());
        }
        let mut matches: Vec<&str> = self
            .entries
            .keys()
            .map(String::as_str)
            .filter(|p| p.rsplit('/').next() == Some(path))
            .collect();
        matches.sort_unstable();
        match matches[..] {
            [one] => Ok(one.to_owned()),
            [] => Ok(format!("/{path}")),
            _ => Err(HandleError::Ambiguous {
                name: path.to_owned(),
                paths: matches.join(", "),
            }),
        }
    }
}
