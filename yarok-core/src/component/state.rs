//! [`NamedState`]: a value a component publishes under a name — an arm's joints, a gripper's
//! position — read on demand, as JSON, by bridges, recorders and inspectors.

use crate::BoxError;

/// What reads a state's value.
pub(crate) type ReadState = Box<dyn Fn() -> Result<serde_json::Value, BoxError>>;

/// A named, serializable state of one component, registered with
/// [`Bind::state`](super::Bind::state) and listed to plugins by
/// [`World::states`](crate::runtime::World::states).
pub struct NamedState {
    component: String,
    name: String,
    read: ReadState,
}

impl std::fmt::Debug for NamedState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NamedState")
            .field("component", &self.component)
            .field("name", &self.name)
            .finish()
    }
}

impl NamedState {
    pub(crate) fn new(component: String, name: String, read: ReadState) -> Self {
        Self {
            component,
            name,
            read,
        }
    }

    /// The component's path.
    pub fn component(&self) -> &str {
        &self.component
    }

    /// The state's name within its component (`"state"`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The state's path: its component's path, then its name (`/arm/state`).
    pub fn path(&self) -> String {
        super::probe::path_within(&self.component, &self.name)
    }

    /// The value now, as JSON.
    ///
    /// # Errors
    ///
    /// When the value cannot be serialized, naming the state (`state /arm/state: …`).
    pub fn read(&self) -> Result<serde_json::Value, BoxError> {
        (self.read)().map_err(|e| format!("state {}: {e}", self.path()).into())
    }
}
