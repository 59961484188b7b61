//! [`Bind`]: what a component's interface sees while it makes its handle at start-up.

use std::cell::RefCell;
use std::future::Future;
use std::rc::Rc;

use serde::Serialize;
use serde::de::DeserializeOwned;

use super::{
    Actuators, Backend, Environment, HandleError, Handles, Lifecycle, NameKind, NameMap,
    NamedCommand, NamedState, Probe, ProbeImage, StopAction,
};
use crate::BoxError;
use crate::config::ConfigOrigins;
use crate::suggest::did_you_mean_or_list;
use crate::time::Clock;
use crate::value::{Config, SettingsError};

/// Seconds a stop action registered with [`Bind::on_stop`] may take before it is abandoned.
pub const DEFAULT_STOP_SECONDS: f64 = 5.0;

/// A component could not bind.
#[derive(thiserror::Error)]
#[non_exhaustive]
pub enum BindError {
    /// The component's template defines no such name.
    #[error("component {component}: its template has no {kind} named {local:?}{hint}")]
    NoName {
        /// The component's path.
        component: String,
        /// The kind of name looked up.
        kind: NameKind,
        /// The local name asked for.
        local: String,
        /// A "did you mean" suggestion, or nothing.
        hint: String,
    },
    /// A setting or config value does not fit.
    #[error("component {component}: {origin}: {source}")]
    Settings {
        /// The component's path.
        component: String,
        /// Where the value was set (file and key, `--set` argument, or the component's config).
        origin: String,
        /// What is wrong.
        source: SettingsError,
    },
    /// A child component's handle could not be had.
    #[error("component {component}: {source}")]
    Handle {
        /// The component's path.
        component: String,
        /// Why.
        source: HandleError,
    },
    /// Something the interface awaited did not finish in time.
    #[error("component {component}: {what} did not finish within {seconds} s")]
    Timeout {
        /// The component's path.
        component: String,
        /// What was awaited.
        what: String,
        /// The bound.
        seconds: f64,
    },
    /// The interface failed.
    #[error("component {component}: {source}")]
    Failed {
        /// The component's path.
        component: String,
        /// Its error.
        source: BoxError,
    },
}

crate::debug_as_report!(BindError);

/// What the platform hands an interface to bind, whatever its environment.
pub(crate) struct BindContext {
    pub(crate) environment: &'static str,
    pub(crate) path: String,
    pub(crate) config: Config,
    pub(crate) names: NameMap,
    pub(crate) settings: Config,
    pub(crate) origins: Rc<ConfigOrigins>,
    pub(crate) backend: Rc<dyn Backend>,
    pub(crate) handles: Rc<RefCell<Handles>>,
    pub(crate) clock: Clock,
    pub(crate) seed: u64,
    pub(crate) lifecycle: Rc<RefCell<Lifecycle>>,
}

/// The context in which a component's [`Interface`](super::Interface) for environment `E` makes
/// its handle: its path, config and settings, its template's names, `E`'s backend (typed), its
/// bound children, platform time, and the hooks of its life.
///
/// # When each hook runs
///
/// - [`Bind::on_tick`]: after every backend step, before plugins and behaviours see the tick;
///   children's before their parents'.
/// - [`Bind::spawn`]: polled on the platform's thread whenever woken (by a tick it awaits or by
///   I/O, at once) until the run ends; an error ends the run.
/// - [`Bind::on_stop`]: once at shutdown — after behaviours end, fail, or Ctrl-C, and also when
///   a later component fails to bind — in reverse binding order, each bounded in time, whatever
///   the others do.
pub struct Bind<E: Environment> {
    context: BindContext,
    backend: Rc<E::Backend>,
    /// Whether the interface has read its settings.
    settings_read: std::cell::Cell<bool>,
}

impl<E: Environment> std::fmt::Debug for Bind<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Bind")
            .field("environment", &E::NAME)
            .field("path", &self.context.path)
            .finish()
    }
}

impl<E: Environment> Bind<E> {
    pub(crate) fn new(context: BindContext) -> Result<Self, BindError> {
        let backend: Rc<dyn std::any::Any> = context.backend.clone();
        let backend = backend
            .downcast::<E::Backend>()
            .map_err(|_| BindError::Failed {
                component: context.path.clone(),
                source: format!(
                    "the `{}` backend is not the {} its interface needs",
                    context.environment,
                    std::any::type_name::<E::Backend>()
                )
                .into(),
            })?;
        Ok(Self {
            context,
            backend,
            settings_read: std::cell::Cell::new(false),
        })
    }

    /// Warns when the run configuration gave this component's interface settings that it never
    /// read (they would change nothing): once it is bound.
    pub(crate) fn warn_unread_settings(&self) {
        if self.settings_read.get() || self.context.settings.is_empty() {
            return;
        }
        let keys: Vec<&str> = self.context.settings.keys().collect();
        let origins: Vec<String> = keys
            .iter()
            .map(|key| {
                self.context
                    .origins
                    .describe("interfaces", &self.context.path, key)
            })
            .collect();
        tracing::warn!(
            "component {}: its `{}` interface takes no settings; {} ({}) changed nothing",
            self.context.path,
            self.context.environment,
            keys.join(", "),
            origins.join(", ")
        );
    }

    /// The environment's backend.
    pub fn backend(&self) -> &E::Backend {
        &self.backend
    }

    /// The component's path (`/printer`).
    pub fn path(&self) -> &str {
        &self.context.path
    }

    /// The component's config (see [`Declaration::config`](super::Declaration::config)) with
    /// defaults, tag attributes and run settings applied, read into `C`: the fields `C` has;
    /// other values (a base component's, values only the template uses) are left alone.
    ///
    /// # Errors
    ///
    /// [`BindError::Settings`] when a value does not fit its field (naming the key, and where
    /// it was set when a run configuration set it), or a field without a serde default has no
    /// value.
    pub fn config<C: DeserializeOwned>(&self) -> Result<C, BindError> {
        self.context
            .config
            .deserialize_fields()
            .map_err(|source: SettingsError| {
                let set_by_run = source.key.as_deref().and_then(|key| {
                    self.context
                        .origins
                        .of("components", &self.context.path, key)
                });
                let origin = set_by_run.unwrap_or("its config").to_owned();
                self.settings_error(origin, source)
            })
    }

    /// The interface's settings (`[interfaces."/path"]` in the run configuration), read into
    /// `T`: a serde struct, usually `#[serde(default)]` so that every key is optional.
    ///
    /// # Errors
    ///
    /// [`BindError::Settings`] naming where the bad value was set: an unknown key (with the
    /// nearest one), or a value of the wrong type.
    pub fn settings<T: DeserializeOwned>(&self) -> Result<T, BindError> {
        self.settings_read.set(true);
        self.context
            .settings
            .deserialize()
            .map_err(|source: SettingsError| {
                let origin = match &source.key {
                    Some(key) => self.context.origins.describe(
                        "interfaces",
                        &self.context.path,
                        key.split('.').next().unwrap_or(key),
                    ),
                    None => "run configuration".into(),
                };
                self.settings_error(origin, source)
            })
    }

    fn settings_error(&self, origin: String, source: SettingsError) -> BindError {
        BindError::Settings {
            component: self.context.path.clone(),
            origin,
            source,
        }
    }

    /// The composed-model name of something the component's template calls `local`.
    ///
    /// # Errors
    ///
    /// [`BindError::NoName`] when the template defines no such name.
    pub fn name(&self, kind: NameKind, local: &str) -> Result<&str, BindError> {
        self.context
            .names
            .get(kind, local)
            .ok_or_else(|| BindError::NoName {
                component: self.context.path.clone(),
                kind,
                local: local.to_owned(),
                hint: did_you_mean_or_list(
                    local,
                    self.context
                        .names
                        .iter()
                        .filter(|(k, _, _)| *k == kind)
                        .map(|(_, local, _)| local),
                ),
            })
    }

    /// The handle of a child component (bound before its parent), by name.
    ///
    /// # Errors
    ///
    /// [`BindError::Handle`] when there is no such child or it is another type.
    pub fn child<C: Clone + 'static>(&self, name: &str) -> Result<C, BindError> {
        let path = if self.context.path == "/" {
            format!("/{name}")
        } else {
            format!("{}/{name}", self.context.path)
        };
        self.context
            .handles
            .borrow()
            .get::<C>(&path)
            .map_err(|source| BindError::Handle {
                component: self.context.path.clone(),
                source,
            })
    }

    /// Platform time, for tasks the interface spawns (`clock.tick().await` each tick).
    pub fn clock(&self) -> Clock {
        self.context.clock.clone()
    }

    /// A seed for this component's random numbers, derived from `[platform] seed` and its path:
    /// the same run configuration gives the same numbers, and two components differ.
    pub fn seed(&self) -> u64 {
        self.context.seed
    }

    /// Registers work to do after every backend step (children's before their parents'). The
    /// clock has advanced before it runs: [`Clock::time`](crate::time::Clock::time) reads the time
    /// the step reached.
    pub fn on_tick(&mut self, step: impl FnMut() -> Result<(), BoxError> + 'static) {
        let span = tracing::info_span!("component", path = %self.context.path);
        self.context.lifecycle.borrow_mut().ticks.push((
            self.context.path.clone(),
            span,
            Box::new(step),
        ));
    }

    /// Spawns a task on the platform's thread that lives as long as the run: a device reader, a
    /// heartbeat, a per-tick loop that awaits (`loop { clock.tick().await?; … }`). It is polled
    /// whenever woken, by I/O at once; it is dropped at shutdown, before the stop actions run.
    /// An error it returns ends the run, naming the component.
    pub fn spawn(&mut self, task: impl Future<Output = Result<(), BoxError>> + 'static) {
        let span = tracing::info_span!("component", path = %self.context.path);
        self.context.lifecycle.borrow_mut().tasks.push((
            self.context.path.clone(),
            Box::pin(tracing::Instrument::instrument(task, span)),
        ));
    }

    /// Registers a probe: an image of what the component senses, named `name` within it, which
    /// `read` makes when an inspector or a recorder asks (see
    /// [`World::probes`](crate::runtime::World::probes)).
    pub fn probe(&mut self, name: &str, read: impl Fn() -> Result<ProbeImage, BoxError> + 'static) {
        self.context.lifecycle.borrow_mut().probes.push(Probe::new(
            self.context.path.clone(),
            name.to_owned(),
            Box::new(read),
        ));
    }

    /// Publishes a state named `name` within the component: `read` gives its value (any
    /// serializable value, usually a struct) when a bridge, a recorder or an inspector asks
    /// (see [`World::states`](crate::runtime::World::states)). The Zenoh bridge publishes it
    /// at `…{path}/{name}`; the MCAP recorder records it on the topic `{path}/{name}`.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::cell::Cell;
    /// use std::rc::Rc;
    /// use yarok_core::component::{Bind, BindError, Mock};
    ///
    /// #[derive(Clone)]
    /// struct Fan { speed: Rc<Cell<f64>> }
    ///
    /// #[derive(serde::Serialize)]
    /// struct FanState { speed: f64 }
    ///
    /// #[derive(serde::Deserialize)]
    /// struct SetSpeed { speed: f64 }
    ///
    /// fn bind(bind: &mut Bind<Mock>) -> Result<Fan, BindError> {
    ///     let fan = Fan { speed: Rc::new(Cell::new(0.0)) };
    ///     let speed = Rc::clone(&fan.speed);
    ///     bind.state("state", move || FanState { speed: speed.get() });
    ///     let speed = Rc::clone(&fan.speed);
    ///     bind.command("set_speed", move |SetSpeed { speed: to }| {
    ///         speed.set(to);
    ///         Ok(())
    ///     });
    ///     Ok(fan)
    /// }
    /// ```
    pub fn state<T: Serialize>(&mut self, name: &str, read: impl Fn() -> T + 'static) {
        self.context
            .lifecycle
            .borrow_mut()
            .states
            .push(NamedState::new(
                self.context.path.clone(),
                name.to_owned(),
                Box::new(move || Ok(serde_json::to_value(read())?)),
            ));
    }

    /// Accepts a command named `name` within the component: `run` gets its body, read from
    /// JSON into `T`, when a bridge or an inspector sends one (see
    /// [`World::commands`](crate::runtime::World::commands)); it starts what the command asks
    /// and returns at once. The Zenoh bridge takes it at `…{path}/{name}`. See
    /// [`Bind::state`] for an example.
    pub fn command<T: DeserializeOwned>(
        &mut self,
        name: &str,
        run: impl Fn(T) -> Result<(), BoxError> + 'static,
    ) {
        self.context
            .lifecycle
            .borrow_mut()
            .commands
            .push(NamedCommand::new(
                self.context.path.clone(),
                name.to_owned(),
                // The path names the field a body got wrong (`brightness: invalid type: …`).
                Box::new(move |body| run(serde_path_to_error::deserialize(body)?)),
            ));
    }

    /// Registers how a policy observes and drives the component's `actuators` — each named as
    /// the composed model names it (`arm/shoulder_pan`), with the range of its target, lowest
    /// first (targets outside are refused before `set` sees them): `measured` reads where they
    /// are now (what a policy observes of them, in `sim` and on hardware alike), `target` the
    /// targets they are commanded to reach a given number of seconds ahead (what a dataset
    /// records as the action of a frame: what a policy must output for the next period to
    /// go as it went; a motion's reference that far along, a streamed target), `set` sets new ones
    /// (what a policy's action does). Listed to plugins by
    /// [`World::actuations`](crate::runtime::World::actuations); a world's action is every
    /// component's, in binding order.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::cell::Cell;
    /// use std::rc::Rc;
    /// use yarok_core::component::{Bind, BindError, Mock};
    ///
    /// fn bind(bind: &mut Bind<Mock>) -> Result<Rc<Cell<f64>>, BindError> {
    ///     // A mock slide that is where it is told to be at once.
    ///     let target = Rc::new(Cell::new(0.0));
    ///     let (at, read, set) = (Rc::clone(&target), Rc::clone(&target), Rc::clone(&target));
    ///     bind.actuation(
    ///         [("slide/motor".to_owned(), [-1.0, 1.0])],
    ///         move || vec![at.get()],
    ///         move |_ahead| vec![read.get()],
    ///         move |targets| {
    ///             set.set(targets[0]);
    ///             Ok(())
    ///         },
    ///     );
    ///     Ok(target)
    /// }
    /// ```
    pub fn actuation(
        &mut self,
        actuators: impl IntoIterator<Item = (String, [f64; 2])>,
        measured: impl Fn() -> Vec<f64> + 'static,
        target: impl Fn(f64) -> Vec<f64> + 'static,
        set: impl Fn(&[f64]) -> Result<(), BoxError> + 'static,
    ) {
        let (names, ranges) = actuators.into_iter().unzip();
        let actuators = Actuators {
            names,
            ranges,
            measured: Box::new(measured),
            target: Box::new(target),
            set: Box::new(set),
        };
        self.context
            .lifecycle
            .borrow_mut()
            .actuations
            .push(super::NamedActuation::new(
                self.context.path.clone(),
                "action".to_owned(),
                Box::new(actuators),
            ));
    }

    /// Registers what puts the component's own state back (a target, a schedule, a count) when
    /// an episode begins and the world goes back to its start state
    /// ([`Pl::begin_episode`](crate::runtime::Pl::begin_episode)): the backend's state is put
    /// back first, then every component's restart action runs, in binding order.
    pub fn on_restart(&mut self, action: impl FnMut() + 'static) {
        self.context
            .lifecycle
            .borrow_mut()
            .restarts
            .push(Box::new(action));
    }

    /// Registers an action that leaves the component safe at shutdown (stop motion, close the
    /// port), abandoned after [`DEFAULT_STOP_SECONDS`]; see [`Bind::on_stop_within`].
    pub fn on_stop(&mut self, action: impl Future<Output = Result<(), BoxError>> + 'static) {
        self.on_stop_within(DEFAULT_STOP_SECONDS, action);
    }

    /// Registers a stop action abandoned after `seconds` (of the wall clock, which is platform
    /// time on hardware). Stop actions run in reverse binding order, each whatever the others
    /// did; a failure or timeout is reported and the next one still runs.
    pub fn on_stop_within(
        &mut self,
        seconds: f64,
        action: impl Future<Output = Result<(), BoxError>> + 'static,
    ) {
        let span = tracing::info_span!("component", path = %self.context.path);
        self.context.lifecycle.borrow_mut().stops.push(StopAction {
            component: self.context.path.clone(),
            seconds,
            action: Box::pin(tracing::Instrument::instrument(action, span)),
        });
    }

    /// Awaits `future` for at most `seconds` of the wall clock (no tick runs while components
    /// bind; on hardware the wall clock is platform time); `what` names it in the error.
    ///
    /// # Errors
    ///
    /// [`BindError::Timeout`] when the time runs out first.
    pub async fn within<T>(
        &self,
        seconds: f64,
        what: &str,
        future: impl Future<Output = T>,
    ) -> Result<T, BindError> {
        let timeout = |seconds| BindError::Timeout {
            component: self.context.path.clone(),
            what: what.to_owned(),
            seconds,
        };
        let duration = std::time::Duration::try_from_secs_f64(seconds).map_err(|_| timeout(0.0))?;
        tokio::time::timeout(duration, future)
            .await
            .map_err(|_| timeout(seconds))
    }

    /// A binding error naming this component.
    pub fn error(&self, source: impl Into<BoxError>) -> BindError {
        BindError::Failed {
            component: self.context.path.clone(),
            source: source.into(),
        }
    }
}
