//! [`Plugin`]: code that runs beside the behaviours and sees the world (viewers, loggers,
//! recorders).

use super::Pl;
use crate::BoxError;
use crate::component::{Backend, NamedActuation, NamedCommand, NamedState, Probe};
use crate::compose::Composition;
use crate::config::Settings;

/// What a plugin sees: the backend (for `sim`: MuJoCo's model, data and renderers), the composed
/// world (component tree, names), the run's settings, and through [`World::pl`] platform time
/// and the components' handles.
#[derive(Clone, Copy)]
pub struct World<'a> {
    pub(crate) pl: &'a Pl,
    pub(crate) backend: &'a dyn Backend,
    pub(crate) composition: &'a Composition,
    pub(crate) settings: &'a Settings,
    pub(crate) probes: &'a [Probe],
    pub(crate) states: &'a [NamedState],
    pub(crate) commands: &'a [NamedCommand],
    pub(crate) actuations: &'a [NamedActuation],
}

impl std::fmt::Debug for World<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("World").field("pl", self.pl).finish()
    }
}

impl<'a> World<'a> {
    /// Platform time, waits and the components' handles.
    pub fn pl(&self) -> &'a Pl {
        self.pl
    }

    /// The backend as its concrete type (`SimBackend` in `sim`), or `None` in another
    /// environment.
    pub fn backend<B: Backend>(&self) -> Option<&'a B> {
        let backend: &'a dyn std::any::Any = self.backend;
        backend.downcast_ref()
    }

    /// The composed world: every component's path, type, config and names.
    pub fn composition(&self) -> &'a Composition {
        self.composition
    }

    /// The run's settings.
    pub fn settings(&self) -> &'a Settings {
        self.settings
    }

    /// What behaviours did since the plugins' last step (at the first step, since the
    /// behaviours started; at the end, since the last step), in order: the lines they logged
    /// ([`Pl::log`]) and the episodes they began and ended ([`Pl::begin_episode`]).
    pub fn happenings(&self) -> std::cell::Ref<'a, [super::Happening]> {
        self.pl.happenings()
    }

    /// Puts the world back into its start state as an episode's beginning does
    /// ([`Pl::begin_episode`]), without beginning one: a viewer's reset. Platform time goes on.
    ///
    /// # Errors
    ///
    /// What keeps the backend from going back (a plugin still borrowing the simulation data).
    pub fn restart(&self) -> Result<(), crate::BoxError> {
        self.pl.restart_world()
    }

    /// Every component's probes (images of what it senses), in binding order.
    pub fn probes(&self) -> &'a [Probe] {
        self.probes
    }

    /// Every component's named states, in binding order.
    pub fn states(&self) -> &'a [NamedState] {
        self.states
    }

    /// Every component's named commands, in binding order.
    pub fn commands(&self) -> &'a [NamedCommand] {
        self.commands
    }

    /// Every component's actuation (how a policy drives its actuators), in binding order:
    /// together, the world's action.
    pub fn actuations(&self) -> &'a [NamedActuation] {
        self.actuations
    }

    /// The command `name` of the component at `path`, if it accepts one.
    pub fn command(&self, path: &str, name: &str) -> Option<&'a NamedCommand> {
        self.commands
            .iter()
            .find(|command| command.component() == path && command.name() == name)
    }
}

/// A plugin: started before the first tick, stepped after every tick's backend and component
/// steps (in the order plugins were added), ended at shutdown.
///
/// # Lifecycle
///
/// 1. [`Plugin::start`] once, after components are bound and before behaviours start;
/// 2. [`Plugin::step`] after every tick's backend and component steps, before behaviours see it;
///    the clock has already advanced, so [`Clock::time`](crate::time::Clock::time) and
///    [`Clock::ticks`](crate::time::Clock::ticks) read the tick being stepped (the backend's time
///    and its count of steps), as they do for components' [`on_tick`](crate::component::Bind::on_tick)
///    and for behaviours woken by it;
/// 3. [`Plugin::end`] once at shutdown, whatever ended the run, before the components' stop
///    actions.
///
/// # Examples
///
/// ```
/// use yarok_core::runtime::{Plugin, World};
///
/// /// Counts ticks and says how many at the end.
/// #[derive(Default)]
/// struct TickCounter(u64);
///
/// impl Plugin for TickCounter {
///     fn step(&mut self, _: &World<'_>) -> Result<(), yarok_core::BoxError> {
///         self.0 += 1;
///         Ok(())
///     }
///     fn end(&mut self, world: &World<'_>) -> Result<(), yarok_core::BoxError> {
///         println!("{} ticks, {} s", self.0, world.pl().time());
///         Ok(())
///     }
/// }
/// ```
pub trait Plugin: 'static {
    /// The plugin's name, for messages.
    fn name(&self) -> String {
        std::any::type_name::<Self>().to_owned()
    }

    /// The files the plugin writes (a recorder's): the platform refuses, before the run starts,
    /// two plugins that would write the same file.
    fn writes(&self) -> Vec<std::path::PathBuf> {
        Vec::new()
    }

    /// The environments the plugin runs in, by their
    /// [`NAME`](crate::component::Environment::NAME); empty (the default) for any. The platform
    /// refuses the plugin in another before anything binds, naming the plugin and the
    /// environments it runs in, as it refuses components.
    fn environments(&self) -> Vec<&'static str> {
        Vec::new()
    }

    /// Called once before the first tick.
    ///
    /// # Errors
    ///
    /// An error stops the platform before behaviours run.
    fn start(&mut self, _world: &World<'_>) -> Result<(), BoxError> {
        Ok(())
    }

    /// Called after every tick.
    ///
    /// # Errors
    ///
    /// An error shuts the platform down and is returned from `run`.
    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError>;

    /// Called once when the run ends (flush files, close windows).
    ///
    /// # Errors
    ///
    /// Returned from `run` when nothing else failed first.
    fn end(&mut self, _world: &World<'_>) -> Result<(), BoxError> {
        Ok(())
    }
}

impl<F: FnMut(&World<'_>) -> Result<(), BoxError> + 'static> Plugin for F {
    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self(world)
    }
}
