//! [`NamedCommand`]: something a component accepts under a name — a motion, a grip — run with a
//! JSON body by bridges and inspectors.

use super::Named;
use crate::BoxError;

/// A named command one component accepts — run with a JSON body — registered with
/// [`Bind::command`](super::Bind::command) and listed to plugins by
/// [`World::commands`](crate::runtime::World::commands).
pub type NamedCommand = Named<dyn Fn(serde_json::Value) -> Result<(), BoxError>>;

impl NamedCommand {
    /// Runs the command with `body` (JSON): it starts what it asks for and returns; waiting
    /// for the motion to end is the caller's.
    ///
    /// # Errors
    ///
    /// When the body does not fit the command or the component refuses it, naming the command
    /// (`command /arm/command: …`).
    pub fn run(&self, body: serde_json::Value) -> Result<(), BoxError> {
        (self.function())(body).map_err(|e| format!("command {}: {e}", self.path()).into())
    }
}
