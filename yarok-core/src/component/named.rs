//! [`Named`]: what a component registers under a name — a probe, a state, a command — with the
//! function behind it, listed to plugins by the world.

use std::fmt;

/// Something one component registers under a name, with the function `F` that reads or runs
/// it: a [`Probe`](super::Probe), a [`NamedState`](super::NamedState) or a
/// [`NamedCommand`](super::NamedCommand).
pub struct Named<F: ?Sized> {
    component: String,
    name: String,
    function: Box<F>,
}

impl<F: ?Sized> fmt::Debug for Named<F> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Named")
            .field("component", &self.component)
            .field("name", &self.name)
            .finish()
    }
}

impl<F: ?Sized> Named<F> {
    pub(crate) fn new(component: String, name: String, function: Box<F>) -> Self {
        Self {
            component,
            name,
            function,
        }
    }

    /// The component's path.
    pub fn component(&self) -> &str {
        &self.component
    }

    /// The name within its component (a probe's `"image"`, an arm's `"state"` and
    /// `"command"`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The path: its component's path, then its name (`/arm/state`; `/state` for the world's
    /// own).
    pub fn path(&self) -> String {
        format!("{}/{}", self.component.trim_end_matches('/'), self.name)
    }

    pub(crate) fn function(&self) -> &F {
        &self.function
    }
}
