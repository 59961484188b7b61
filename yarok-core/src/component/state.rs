//! [`NamedState`]: a value a component publishes under a name — an arm's joints, a gripper's
//! position — read on demand, as JSON, by bridges, recorders and inspectors.

use super::Named;
use crate::BoxError;

/// A named, serializable state of one component — read on demand as JSON — registered with
/// [`Bind::state`](super::Bind::state) and listed to plugins by
/// [`World::states`](crate::runtime::World::states).
pub type NamedState = Named<dyn Fn() -> Result<serde_json::Value, BoxError>>;

impl NamedState {
    /// The value now, as JSON.
    ///
    /// # Errors
    ///
    /// When the value cannot be serialized, naming the state (`state /arm/state: …`).
    pub fn read(&self) -> Result<serde_json::Value, BoxError> {
        (self.function())().map_err(|e| format!("state {}: {e}", self.path()).into())
    }
}
