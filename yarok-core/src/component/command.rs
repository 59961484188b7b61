//! [`NamedCommand`]: something a component accepts under a name — a motion, a grip — run with a
//! JSON body by bridges and inspectors.

use crate::BoxError;

/// What runs a command with its body.
pub(crate) type RunCommand = Box<dyn Fn(serde_json::Value) -> Result<(), BoxError>>;

/// A named command one component accepts, registered with
/// [`Bind::command`](super::Bind::command) and listed to plugins by
/// [`World::commands`](crate::runtime::World::commands).
pub struct NamedCommand {
    component: String,
    name: String,
    run: RunCommand,
}

impl std::fmt::Debug for NamedCommand {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NamedCommand")
            .field("component", &self.component)
            .field("name", &self.name)
            .finish()
    }
}

impl NamedCommand {
    pub(crate) fn new(component: String, name: String, run: RunCommand) -> Self {
        Self {
            component,
            name,
            run,
        }
    }

    /// The component's path.
    pub fn component(&self) -> &str {
        &self.component
    }

    /// The command's name within its component (`"command"`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The command's path: its component's path, then its name (`/arm/command`).
    pub fn path(&self) -> String {
        super::probe::path_within(&self.component, &self.name)
    }

    /// Runs the command with `body` (JSON): it starts what it asks for and returns; waiting
    /// for the motion to end is the caller's.
    ///
    /// # Errors
    ///
    /// When the body does not fit the command or the component refuses it, naming the command
    /// (`command /arm/command: …`).
    pub fn run(&self, body: serde_json::Value) -> Result<(), BoxError> {
        (self.run)(body).map_err(|e| format!("command {}: {e}", self.path()).into())
    }
}
