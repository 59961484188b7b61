//! [`Plugin`]: code that runs every tick beside the behaviours (viewers, loggers, recorders).

use super::{BoxError, Pl};

/// A plugin: stepped every tick after the components' interfaces, in the order plugins were
/// added; told when the run ends.
///
/// # Lifecycle
///
/// 1. [`Plugin::start`] once, after components are bound and before the first tick;
/// 2. [`Plugin::step`] after every tick's backend and interface steps;
/// 3. [`Plugin::on_end`] once at shutdown, whatever ended the run (in the same order).
pub trait Plugin: 'static {
    /// The plugin's name, for messages.
    fn name(&self) -> String {
        std::any::type_name::<Self>().to_owned()
    }

    /// Called once before the first tick.
    ///
    /// # Errors
    ///
    /// An error stops the platform before it runs.
    fn start(&mut self, _pl: &Pl) -> Result<(), BoxError> {
        Ok(())
    }

    /// Called after every tick.
    ///
    /// # Errors
    ///
    /// An error shuts the platform down and is returned from `run`.
    fn step(&mut self, pl: &Pl) -> Result<(), BoxError>;

    /// Called once when the run ends.
    fn on_end(&mut self, _pl: &Pl) {}
}

impl<F: FnMut(&Pl) -> Result<(), BoxError> + 'static> Plugin for F {
    fn step(&mut self, pl: &Pl) -> Result<(), BoxError> {
        self(pl)
    }
}
