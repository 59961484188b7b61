//! [`Platform`]: composes the world, binds components to a backend and runs behaviours on ticks.

use std::collections::{BTreeMap, HashMap};
use std::future::Future;
use std::pin::Pin;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::task::{Context, Poll, Wake, Waker};

use super::bind::{Bind, Handle, Step};
use super::interrupt::Interrupt;
use super::wait::{Clock, Wait, WaitError};
use super::{Backend, BackendFactory, BoxError, Plugin, RuntimeError};
use crate::compose::{Component, ComponentType, Composition, Config, Value, compose_configured};
use crate::config::{ConfigOrigins, RunConfig, Settings};
use crate::suggest::did_you_mean;

/// What a behaviour returns.
pub type BehaviourResult = Result<(), BoxError>;

type Behaviour = Pin<Box<dyn Future<Output = BehaviourResult>>>;
type BehaviourFactory = (String, Box<dyn FnOnce(Pl) -> Behaviour>);
type PluginFactory = Box<dyn Fn(&Config) -> Result<Box<dyn Plugin>, BoxError>>;

/// Ticks between yields to the tokio scheduler when the simulation runs unpaced, so that Ctrl-C
/// and other tasks are served without slowing stepping.
const YIELD_EVERY: u64 = 64;
/// Polling rounds per tick after which behaviours that keep waking themselves are left for the
/// next tick.
const MAX_ROUNDS: usize = 1000;

/// The handle behaviours and plugins use: platform time, waits, components.
///
/// Cheap to clone; lives on the platform's thread (it is not `Send`).
#[derive(Clone)]
pub struct Pl {
    inner: Rc<Shared>,
}

struct Shared {
    clock: Clock,
    environment: String,
    handles: HashMap<String, Handle>,
    paths: Vec<(String, ComponentType)>,
    behaviour: Config,
    stop: Arc<AtomicBool>,
}

impl std::fmt::Debug for Pl {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pl")
            .field("environment", &self.inner.environment)
            .field("time", &self.time())
            .finish()
    }
}

impl Pl {
    /// Platform time in seconds: simulation time in `sim`, time since start on hardware.
    pub fn time(&self) -> f64 {
        self.inner.clock.time.get()
    }

    /// Ticks since start.
    pub fn ticks(&self) -> u64 {
        self.inner.clock.ticks.get()
    }

    /// Seconds per tick.
    pub fn timestep(&self) -> f64 {
        self.inner.clock.timestep
    }

    /// The running environment.
    pub fn environment(&self) -> &str {
        &self.inner.environment
    }

    /// The behaviour's settings (`[behaviour]`), defaults applied.
    pub fn config(&self) -> &Config {
        &self.inner.behaviour
    }

    /// Resolves on the first tick after which `condition` holds; it is checked after every
    /// tick, and at least one tick passes.
    ///
    /// # Cancel safety
    ///
    /// Cancel safe: dropping the wait changes nothing.
    #[track_caller]
    pub fn wait<C: FnMut() -> bool + Unpin>(&self, condition: C) -> Wait<'_, C> {
        Wait::new(&self.inner.clock, condition)
    }

    /// Resolves once `seconds` of platform time have passed (to the nearest tick).
    /// `f64::INFINITY` waits forever; NaN or a negative number makes the wait fail at once with
    /// [`WaitError::InvalidDuration`](crate::runtime::WaitError::InvalidDuration).
    #[track_caller]
    pub fn wait_seconds(&self, seconds: f64) -> Wait<'_, impl FnMut() -> bool + Unpin + '_> {
        let clock = &self.inner.clock;
        let target = clock.time.get() + seconds - clock.timestep / 2.0;
        Wait::new(clock, move || clock.time.get() >= target)
            .invalid(WaitError::check_duration("wait_seconds", seconds))
    }

    /// Resolves after the next tick.
    #[track_caller]
    pub fn tick(&self) -> Wait<'_, impl FnMut() -> bool + Unpin> {
        Wait::new(&self.inner.clock, || true)
    }

    /// Never resolves on its own; ends with an error when the platform stops (or its timeout).
    #[track_caller]
    pub fn wait_forever(&self) -> Wait<'_, impl FnMut() -> bool + Unpin> {
        Wait::new(&self.inner.clock, || false)
    }

    /// The component at `path` (`/arm`, `/arm/gripper`), or the one component named `path`'s
    /// last segment when `path` has no `/`.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::NoComponent`] (with the nearest path), [`RuntimeError::WrongType`], or
    /// [`RuntimeError::NoHandle`] for a component without a run-time interface.
    pub fn get<C: Component + Clone>(&self, path: &str) -> Result<C, RuntimeError> {
        let path = if path.starts_with('/') {
            path.to_owned()
        } else {
            let matches: Vec<&str> = self
                .inner
                .paths
                .iter()
                .map(|(p, _)| p.as_str())
                .filter(|p| p.rsplit('/').next() == Some(path))
                .collect();
            match matches[..] {
                [one] => one.to_owned(),
                [] => format!("/{path}"),
                _ => {
                    return Err(RuntimeError::Ambiguous {
                        name: path.to_owned(),
                        paths: matches.join(", "),
                    });
                }
            }
        };
        if let Some((_, found)) = self.inner.paths.iter().find(|(p, _)| *p == path)
            && found.type_id() != std::any::TypeId::of::<C>()
        {
            return Err(RuntimeError::WrongType {
                path,
                expected: std::any::type_name::<C>(),
                found: found.type_name(),
            });
        }
        handle(&self.inner.handles, &path)
    }

    /// Asks the platform to stop after the current tick; `run` then returns `Ok`.
    pub fn stop(&self) {
        self.inner.stop.store(true, Ordering::Relaxed);
    }
}

/// Looks up and clones a bound handle.
pub(crate) fn handle<C: Component + Clone>(
    handles: &HashMap<String, Handle>,
    path: &str,
) -> Result<C, RuntimeError> {
    match handles.get(path) {
        None => Err(RuntimeError::NoComponent {
            path: path.to_owned(),
            hint: did_you_mean(path, handles.keys().map(String::as_str)),
        }),
        Some(None) => Err(RuntimeError::NoHandle {
            path: path.to_owned(),
        }),
        Some(Some(handle)) => {
            handle
                .downcast_ref::<C>()
                .cloned()
                .ok_or_else(|| RuntimeError::WrongType {
                    path: path.to_owned(),
                    expected: std::any::type_name::<C>(),
                    found: "another component type",
                })
        }
    }
}

/// Builds a [`Platform`].
pub struct PlatformBuilder {
    world: Option<ComponentType>,
    config: RunConfig,
    default_environment: String,
    backends: BTreeMap<String, BackendFactory>,
    behaviours: Vec<BehaviourFactory>,
    behaviour_defaults: Config,
    plugins: Vec<Box<dyn Plugin>>,
    plugin_factories: BTreeMap<String, PluginFactory>,
    stop: Arc<AtomicBool>,
    ctrl_c: bool,
}

impl std::fmt::Debug for PlatformBuilder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PlatformBuilder")
            .field("world", &self.world)
            .field("config", &self.config)
            .finish()
    }
}

/// A platform ready to run: world composed, components bound, plugins made.
pub struct Platform {
    pl: Pl,
    backend: Box<dyn Backend>,
    steps: Vec<(String, Step)>,
    plugins: Vec<Box<dyn Plugin>>,
    behaviours: Vec<BehaviourFactory>,
    composition: Composition,
    realtime: bool,
    ctrl_c: bool,
}

impl std::fmt::Debug for Platform {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Platform").field("pl", &self.pl).finish()
    }
}

impl Platform {
    /// A builder with no world, no backends, environment `sim` unless configured otherwise.
    pub fn builder() -> PlatformBuilder {
        PlatformBuilder {
            world: None,
            config: RunConfig::default(),
            default_environment: "sim".to_owned(),
            backends: BTreeMap::new(),
            behaviours: Vec::new(),
            behaviour_defaults: Config::default(),
            plugins: Vec::new(),
            plugin_factories: BTreeMap::new(),
            stop: Arc::new(AtomicBool::new(false)),
            ctrl_c: true,
        }
    }

    /// The platform handle.
    pub fn pl(&self) -> &Pl {
        &self.pl
    }

    /// The composed world.
    pub fn composition(&self) -> &Composition {
        &self.composition
    }

    /// A flag that stops the platform after the current tick when set, from any thread.
    pub fn stop_flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.pl.inner.stop)
    }

    /// Runs on a new single-threaded tokio runtime until the behaviours finish, one fails, a
    /// plugin fails, the platform is stopped, or Ctrl-C.
    ///
    /// # Errors
    ///
    /// The first behaviour, plugin or backend error; [`RuntimeError::Interrupted`] on Ctrl-C.
    pub fn run(self) -> Result<(), RuntimeError> {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .map_err(|e| RuntimeError::Backend(format!("cannot start tokio: {e}")))?;
        let local = tokio::task::LocalSet::new();
        local.block_on(&runtime, self.run_local())
    }

    /// Runs inside the caller's tokio runtime (current-thread, or a `LocalSet`): the same loop as
    /// [`Platform::run`], for embedding.
    ///
    /// # Errors
    ///
    /// As [`Platform::run`].
    pub async fn run_local(mut self) -> Result<(), RuntimeError> {
        let mut tasks = Vec::new();
        let result = self.run_loop(&mut tasks).await;
        // Pending waits now fail with `WaitError::Stopped`, so behaviours can clean up; what
        // they return after the end no longer changes the result.
        self.pl.inner.clock.stopped.set(true);
        self.pl.inner.clock.wake_all();
        let _after_the_end = poll_tasks(&mut tasks);
        for plugin in &mut self.plugins {
            plugin.on_end(&self.pl);
        }
        self.backend.stop();
        result
    }

    async fn run_loop(&mut self, tasks: &mut Vec<Task>) -> Result<(), RuntimeError> {
        for plugin in &mut self.plugins {
            plugin
                .start(&self.pl)
                .map_err(|source| RuntimeError::Plugin {
                    name: plugin.name(),
                    source,
                })?;
        }
        tasks.extend(
            std::mem::take(&mut self.behaviours)
                .into_iter()
                .map(|(name, f)| Task::new(name, f(self.pl.clone()))),
        );
        let interrupt = self.ctrl_c.then(Interrupt::listen);
        let started = tokio::time::Instant::now();
        let paced = self.realtime || self.backend.paced();
        poll_tasks(tasks)?;
        loop {
            if tasks.iter().all(|t| t.done) || self.pl.inner.stop.load(Ordering::Relaxed) {
                return Ok(());
            }
            let ticks = self.pl.ticks() + 1;
            if paced {
                // On hardware a tick happens at its due time, so tick n reads time n·timestep.
                let due = started
                    + std::time::Duration::from_secs_f64(ticks as f64 * self.backend.timestep());
                tokio::time::sleep_until(due).await;
            } else if ticks.is_multiple_of(YIELD_EVERY) {
                tokio::task::yield_now().await;
            }
            self.backend.step()?;
            for (path, step) in &mut self.steps {
                step().map_err(|source| RuntimeError::Interface {
                    component: path.clone(),
                    source,
                })?;
            }
            for plugin in &mut self.plugins {
                plugin
                    .step(&self.pl)
                    .map_err(|source| RuntimeError::Plugin {
                        name: plugin.name(),
                        source,
                    })?;
            }
            self.pl.inner.clock.tick(self.backend.time());
            poll_tasks(tasks)?;
            if interrupt.as_ref().is_some_and(Interrupt::happened) {
                return Err(RuntimeError::Interrupted);
            }
        }
    }
}

/// A behaviour being driven by the platform: polled when woken, until done.
struct Task {
    name: String,
    future: Behaviour,
    woken: Arc<Flag>,
    waker: Waker,
    done: bool,
}

struct Flag(AtomicBool);

impl Wake for Flag {
    fn wake(self: Arc<Self>) {
        self.0.store(true, Ordering::Relaxed);
    }
}

impl Task {
    fn new(name: String, future: Behaviour) -> Self {
        let woken = Arc::new(Flag(AtomicBool::new(true)));
        let waker = Waker::from(Arc::clone(&woken));
        Self {
            name,
            future,
            woken,
            waker,
            done: false,
        }
    }
}

/// Polls woken behaviours until none is woken (or `MAX_ROUNDS`).
fn poll_tasks(tasks: &mut [Task]) -> Result<(), RuntimeError> {
    for _ in 0..MAX_ROUNDS {
        let mut progressed = false;
        for (index, task) in tasks.iter_mut().enumerate() {
            if task.done || !task.woken.0.swap(false, Ordering::Relaxed) {
                continue;
            }
            progressed = true;
            let mut context = Context::from_waker(&task.waker);
            if let Poll::Ready(result) = task.future.as_mut().poll(&mut context) {
                task.done = true;
                result.map_err(|source| RuntimeError::Behaviour {
                    index,
                    name: std::mem::take(&mut task.name),
                    source,
                })?;
            }
        }
        if !progressed {
            break;
        }
    }
    Ok(())
}

impl PlatformBuilder {
    /// The world: the root component.
    pub fn world<W: Component>(mut self) -> Self {
        self.world = Some(ComponentType::of::<W>());
        self
    }

    /// The world, as a component type value.
    pub fn world_type(mut self, world: ComponentType) -> Self {
        self.world = Some(world);
        self
    }

    /// Overlays a run configuration (later calls win).
    pub fn config(mut self, config: RunConfig) -> Self {
        self.config.merge(config);
        self
    }

    /// Overlays a TOML run configuration file.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Config`] when it cannot be read.
    pub fn config_file(self, path: impl AsRef<std::path::Path>) -> Result<Self, RuntimeError> {
        Ok(self.config(RunConfig::from_file(path)?))
    }

    /// Selects the environment (default `sim`).
    pub fn environment(mut self, environment: &str) -> Self {
        self.config.set_environment(environment);
        self
    }

    /// Sets one value; see [`RunConfig::set`].
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Config`] for a malformed assignment.
    pub fn set(mut self, assignment: &str) -> Result<Self, RuntimeError> {
        self.config.set(assignment)?;
        Ok(self)
    }

    /// Applies command-line arguments: `--env NAME`, `--set TARGET=VALUE`, `--config FILE`.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Config`] for unknown or incomplete arguments.
    pub fn args(mut self, args: impl IntoIterator<Item = String>) -> Result<Self, RuntimeError> {
        let mut args = args.into_iter();
        while let Some(arg) = args.next() {
            let mut value = || {
                args.next().ok_or_else(|| crate::config::ConfigError {
                    origin: "command line".into(),
                    message: format!("{arg} needs a value"),
                })
            };
            match arg.as_str() {
                "--env" => self.config.set_environment(&value()?),
                "--set" => self.config.set(&value()?)?,
                "--config" => self.config.merge(RunConfig::from_file(value()?)?),
                other => {
                    let hint = did_you_mean(other, ["--env", "--set", "--config"]);
                    return Err(crate::config::ConfigError {
                        origin: "command line".into(),
                        message: format!("unknown argument {other:?}{hint}"),
                    }
                    .into());
                }
            }
        }
        Ok(self)
    }

    /// Registers the backend of an environment.
    pub fn backend(
        mut self,
        environment: &str,
        factory: impl FnOnce(&Composition, &Settings) -> Result<Box<dyn Backend>, RuntimeError>
        + 'static,
    ) -> Self {
        self.backends
            .insert(environment.to_owned(), Box::new(factory));
        self
    }

    /// Adds a behaviour; all behaviours run concurrently, sharing the ticks.
    ///
    /// Errors name it: by its function's name (`pick_and_place`), or, for a closure, by where it
    /// was added (`closure at src/main.rs:12:10`); [`PlatformBuilder::behaviour_named`] gives it a
    /// label instead.
    #[track_caller]
    pub fn behaviour<F, Fut>(self, behaviour: F) -> Self
    where
        F: FnOnce(Pl) -> Fut + 'static,
        Fut: Future<Output = BehaviourResult> + 'static,
    {
        let function = std::any::type_name::<F>();
        let name = if function.contains("{{closure}}") {
            format!("closure at {}", std::panic::Location::caller())
        } else {
            function.rsplit("::").next().unwrap_or(function).to_owned()
        };
        self.behaviour_named(name, behaviour)
    }

    /// Adds a behaviour with a label that its errors carry.
    pub fn behaviour_named<F, Fut>(mut self, name: impl Into<String>, behaviour: F) -> Self
    where
        F: FnOnce(Pl) -> Fut + 'static,
        Fut: Future<Output = BehaviourResult> + 'static,
    {
        self.behaviours
            .push((name.into(), Box::new(move |pl| Box::pin(behaviour(pl)))));
        self
    }

    /// A default for the behaviour's settings; `[behaviour]` keys must have one.
    pub fn behaviour_default(mut self, key: &str, value: impl crate::compose::IntoValue) -> Self {
        self.behaviour_defaults.set(key, value.into_value());
        self
    }

    /// Adds a plugin, stepped in the order added.
    pub fn plugin(mut self, plugin: impl Plugin) -> Self {
        self.plugins.push(Box::new(plugin));
        self
    }

    /// Registers a plugin that `[plugins.<name>]` sections of the run configuration create.
    pub fn plugin_factory(
        mut self,
        name: &str,
        factory: impl Fn(&Config) -> Result<Box<dyn Plugin>, BoxError> + 'static,
    ) -> Self {
        self.plugin_factories
            .insert(name.to_owned(), Box::new(factory));
        self
    }

    /// Composes the world, makes the backend and binds every component (children first).
    ///
    /// When the application has installed no `tracing` subscriber, one is installed that writes
    /// warnings (MuJoCo's among them) to standard error; `RUST_LOG` chooses what else it shows.
    ///
    /// # Errors
    ///
    /// Composition, configuration, backend and binding errors, each naming its place.
    pub fn build(mut self) -> Result<Platform, RuntimeError> {
        report_warnings();
        let world = self.world.ok_or(RuntimeError::NoWorld)?;
        let mut settings = self.config.settings(&self.default_environment);
        for environment in self.config.environments() {
            if !self.backends.contains_key(environment) {
                let hint = did_you_mean(environment, self.backends.keys().map(String::as_str));
                return Err(config_error(format!(
                    "[environments.{environment}] names no known environment{hint}"
                )));
            }
        }
        let factory =
            self.backends
                .remove(&settings.environment)
                .ok_or_else(|| RuntimeError::NoBackend {
                    environment: settings.environment.clone(),
                    available: self.backends.keys().cloned().collect::<Vec<_>>().join(", "),
                })?;
        settings.platform = typed_settings(
            "platform",
            &platform_types(),
            &settings.platform,
            &settings.origins,
        )?;
        let behaviour = defaulted(&self.behaviour_defaults, &settings)?;
        let composition = compose_configured(world, &settings)?;
        for path in settings.interfaces.keys() {
            if composition.instance(path).is_none() {
                let hint =
                    did_you_mean(path, composition.instances.iter().map(|i| i.path.as_str()));
                return Err(config_error(format!(
                    "[interfaces.\"{path}\"] names no component{hint}"
                )));
            }
        }
        let backend = factory(&composition, &settings)?;
        let mut steps = Vec::new();
        let mut handles = HashMap::new();
        let empty = Config::default();
        for instance in composition.instances.iter().rev() {
            let mut bind = Bind {
                environment: &settings.environment,
                instance,
                interface: settings.interfaces.get(&instance.path).unwrap_or(&empty),
                backend: backend.as_ref(),
                steps: &mut steps,
                handles: &handles,
            };
            let handle = match instance.component.bind(&mut bind) {
                Ok(handle) => Some(handle),
                Err(RuntimeError::NoHandle { .. }) => None,
                Err(error) => return Err(error),
            };
            handles.insert(instance.path.clone(), handle);
        }
        for (name, config) in &settings.plugins {
            let factory = self.plugin_factories.get(name).ok_or_else(|| {
                config_error(format!(
                    "[plugins.{name}] names no registered plugin{}",
                    did_you_mean(name, self.plugin_factories.keys().map(String::as_str))
                ))
            })?;
            let plugin = factory(config).map_err(|source| RuntimeError::Plugin {
                name: name.clone(),
                source,
            })?;
            self.plugins.push(plugin);
        }
        let realtime = matches!(
            settings.platform.get("realtime"),
            Some(Value::Boolean(true))
        );
        let paths = composition
            .instances
            .iter()
            .map(|i| (i.path.clone(), i.component))
            .collect();
        let pl = Pl {
            inner: Rc::new(Shared {
                clock: Clock::new(backend.time(), backend.timestep()),
                environment: settings.environment.clone(),
                handles,
                paths,
                behaviour,
                stop: self.stop,
            }),
        };
        Ok(Platform {
            pl,
            backend,
            steps,
            plugins: self.plugins,
            behaviours: self.behaviours,
            composition,
            realtime,
            ctrl_c: self.ctrl_c,
        })
    }

    /// Uses `flag` as the platform's stop flag: setting it, from any thread, stops the platform
    /// after the current tick (see [`Platform::stop_flag`]).
    pub fn stop_flag(mut self, flag: Arc<AtomicBool>) -> Self {
        self.stop = flag;
        self
    }

    /// Whether Ctrl-C stops the platform (default: yes). While it runs, the first Ctrl-C stops it
    /// cleanly ([`RuntimeError::Interrupted`]) and a second one, if shutdown hangs, exits with
    /// status 130; once no platform runs, Ctrl-C ends the process again. An application that
    /// handles Ctrl-C itself (say with `tokio::signal`) passes `false` and stops the platform
    /// through its [stop flag](Platform::stop_flag).
    pub fn ctrl_c(mut self, stops: bool) -> Self {
        self.ctrl_c = stops;
        self
    }

    /// Builds and runs; see [`Platform::run`].
    ///
    /// # Errors
    ///
    /// As [`PlatformBuilder::build`] and [`Platform::run`].
    pub fn run(self) -> Result<(), RuntimeError> {
        self.build()?.run()
    }
}

fn config_error(message: String) -> RuntimeError {
    crate::config::ConfigError {
        origin: "run configuration".into(),
        message,
    }
    .into()
}

/// Sends warnings (MuJoCo's among them) to standard error when the application has installed no
/// `tracing` subscriber of its own, so that none is lost; `RUST_LOG` chooses what else to show.
fn report_warnings() {
    if tracing::dispatcher::has_been_set() {
        return;
    }
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("warn"));
    // Another thread may have installed one since the check: then that one reports.
    let _installed = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .try_init();
}

/// The type of each platform setting, by an example value.
fn platform_types() -> Config {
    Config::from([
        ("realtime", Value::Boolean(false)),
        ("tick_hz", Value::Float(100.0)),
        ("seed", Value::Int(0)),
    ])
}

/// The values `given` in `[section]` (`platform` or `behaviour`), each of the type its key's
/// value in `types` has; an unknown key or a wrong type is an error naming where the value was
/// set.
fn typed_settings(
    section: &str,
    types: &Config,
    given: &Config,
    origins: &ConfigOrigins,
) -> Result<Config, RuntimeError> {
    let mut typed = Config::default();
    for (key, value) in given.iter() {
        let value = crate::compose::typed(types, key, value.clone()).map_err(|message| {
            crate::config::ConfigError {
                origin: origins.describe(section, "", key),
                message: format!("[{section}] {message}"),
            }
        })?;
        typed.set(key, value);
    }
    Ok(typed)
}

/// The behaviour's settings: its defaults, overlaid with the run's `[behaviour]` values.
fn defaulted(defaults: &Config, settings: &Settings) -> Result<Config, RuntimeError> {
    let mut config = defaults.clone();
    let given = typed_settings(
        "behaviour",
        defaults,
        &settings.behaviour,
        &settings.origins,
    )?;
    for (key, value) in given.iter() {
        config.set(key, value.clone());
    }
    Ok(config)
}
