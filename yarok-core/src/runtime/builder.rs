//! [`PlatformBuilder`]: the world, the environments' backends, behaviours, plugins and the run
//! configuration, checked and composed into a [`Platform`].

use std::collections::BTreeMap;
use std::future::Future;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use serde::de::DeserializeOwned;

use super::platform::{BehaviourFactory, Platform, Prepared};
use super::{BehaviourResult, Pl, Plugin, RuntimeError, Unsupported};
use crate::BoxError;
use crate::component::{Backend, ComponentType, Declaration, Environment};
use crate::compose::{Composition, compose_configured, compose_declaration};
use crate::config::{ConfigError, RunConfig, Settings};
use crate::suggest::{did_you_mean, did_you_mean_or_list};
use crate::value::{Config, IntoValue, typed};

type BackendFactory = Box<dyn FnOnce(&Composition, &Settings) -> Result<Rc<dyn Backend>, BoxError>>;
type PluginFactory = Box<dyn Fn(&Settings, &str) -> Result<Box<dyn Plugin>, RuntimeError>>;

/// The world a platform runs: a component type, or a declaration made at run time.
#[derive(Debug)]
enum World {
    Type(ComponentType),
    Declared(Box<Declaration>),
}

/// Builds a [`Platform`].
pub struct PlatformBuilder {
    world: Option<World>,
    config: RunConfig,
    backends: BTreeMap<&'static str, BackendFactory>,
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
            .field("environments", &self.backends.keys())
            .finish()
    }
}

/// The environment selected when the configuration names none.
const DEFAULT_ENVIRONMENT: &str = "sim";

impl PlatformBuilder {
    pub(crate) fn new() -> Self {
        Self {
            world: None,
            config: RunConfig::default(),
            backends: BTreeMap::new(),
            behaviours: Vec::new(),
            behaviour_defaults: Config::default(),
            plugins: Vec::new(),
            plugin_factories: BTreeMap::new(),
            stop: Arc::new(AtomicBool::new(false)),
            ctrl_c: true,
        }
    }

    /// The world: the root component.
    pub fn world<W: crate::component::Component>(self) -> Self {
        self.world_type(ComponentType::of::<W>())
    }

    /// The world, as a component type value.
    pub fn world_type(mut self, world: ComponentType) -> Self {
        self.world = Some(World::Type(world));
        self
    }

    /// A world declared at run time, e.g. from a template file a user names
    /// (`Declaration::new("world").template_file(path)` with the components it may use).
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_core::component::{Declaration, Mock, MockBackend};
    /// use yarok_core::runtime::Platform;
    ///
    /// let world = Declaration::new("world").template(
    ///     r#"<mujoco><worldbody><geom name="floor" size="1 1 0.1"/></worldbody></mujoco>"#,
    /// );
    /// let platform = Platform::builder()
    ///     .world_declaration(world)
    ///     .environment("mock")
    ///     .backend::<Mock>(|_, _| Ok(MockBackend::new(0.5, false)))
    ///     .build()?;
    /// assert!(platform.composition().to_xml().contains("floor"));
    /// # Ok::<(), yarok_core::runtime::RuntimeError>(())
    /// ```
    pub fn world_declaration(mut self, world: Declaration) -> Self {
        self.world = Some(World::Declared(Box::new(world)));
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

    /// Selects the environment by name (default `sim`).
    pub fn environment(mut self, environment: &str) -> Self {
        self.config.set_environment(environment);
        self
    }

    /// Sets one value; see [`RunConfig::set`] for the grammar (the command line's `--set`).
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Config`] for a malformed assignment.
    pub fn set(mut self, assignment: &str) -> Result<Self, RuntimeError> {
        self.config.set(assignment)?;
        Ok(self)
    }

    /// Applies command-line arguments: `--env NAME`, `--set TARGET=VALUE`, `--config FILE`;
    /// strings, or the process's own as the OS gives them (`std::env::args_os().skip(1)`).
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Config`] for unknown or incomplete arguments, and for an argument that
    /// is not UTF-8 (named, with its position).
    pub fn args<A: Into<std::ffi::OsString>>(
        mut self,
        args: impl IntoIterator<Item = A>,
    ) -> Result<Self, RuntimeError> {
        let args: Vec<String> = args
            .into_iter()
            .enumerate()
            .map(|(index, arg)| {
                crate::args::utf8(index + 1, arg.into()).map_err(|message| ConfigError {
                    origin: "command line".into(),
                    message,
                })
            })
            .collect::<Result<_, _>>()?;
        let mut args = args.into_iter();
        while let Some(arg) = args.next() {
            let mut value = || {
                args.next().ok_or_else(|| ConfigError {
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
                    return Err(ConfigError {
                        origin: "command line".into(),
                        message: format!("unknown argument {other:?}{hint}"),
                    }
                    .into());
                }
            }
        }
        Ok(self)
    }

    /// Registers environment `E`: the factory makes its backend from the composed world and the
    /// run settings when `E` is selected.
    pub fn backend<E: Environment>(
        mut self,
        factory: impl FnOnce(&Composition, &Settings) -> Result<E::Backend, BoxError> + 'static,
    ) -> Self {
        self.backends.insert(
            E::NAME,
            Box::new(move |composition, settings| {
                factory(composition, settings).map(|backend| Rc::new(backend) as Rc<dyn Backend>)
            }),
        );
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
    pub fn behaviour_default(mut self, key: &str, value: impl IntoValue) -> Self {
        self.behaviour_defaults.set(key, value.into_value());
        self
    }

    /// Adds a plugin, stepped in the order added.
    pub fn plugin(mut self, plugin: impl Plugin) -> Self {
        self.plugins.push(Box::new(plugin));
        self
    }

    /// Registers a plugin that a `[plugins.<name>]` section of the run configuration creates
    /// (or `--set plugins/<name>/key=value`); the factory gets the section read into its
    /// settings type `S`, a serde struct (unknown keys and wrong types are errors naming the
    /// file and key).
    pub fn plugin_factory<S, P, Error>(
        mut self,
        name: &str,
        factory: impl Fn(S) -> Result<P, Error> + 'static,
    ) -> Self
    where
        S: DeserializeOwned,
        P: Plugin,
        Error: Into<BoxError>,
    {
        self.plugin_factories.insert(
            name.to_owned(),
            Box::new(move |settings, name| {
                let typed = settings.plugin_settings::<S>(name)?;
                let plugin = factory(typed).map_err(|e| RuntimeError::Plugin {
                    name: name.to_owned(),
                    source: e.into(),
                })?;
                Ok(Box::new(plugin) as Box<dyn Plugin>)
            }),
        );
        self
    }

    /// Uses `flag` as the platform's stop flag: setting it, from any thread, stops the platform
    /// after the current tick (see [`Platform::stop_flag`]).
    pub fn stop_flag(mut self, flag: Arc<AtomicBool>) -> Self {
        self.stop = flag;
        self
    }

    /// Whether Ctrl-C, `SIGTERM` and `SIGHUP` stop the platform (default: yes). While it runs, the
    /// first such signal stops it cleanly ([`RuntimeError::Interrupted`] naming it, after the
    /// behaviours saw their waits stopped, the plugins ended — recorders close their files — and
    /// the components' stop actions ran) and a second one, if shutdown hangs, exits with status
    /// 128 + the signal's number (130, 143, 129); once no platform runs, the signals end the
    /// process again. An application that handles signals itself (say with `tokio::signal`)
    /// passes `false` and stops the platform through its [stop flag](Platform::stop_flag).
    pub fn ctrl_c(mut self, stops: bool) -> Self {
        self.ctrl_c = stops;
        self
    }

    /// Composes the world, checks that every component supports the selected environment, and
    /// makes its backend. Components bind when the platform starts (in [`Platform::run`], or the
    /// first [`Platform::step`]).
    ///
    /// When the application has installed no `tracing` subscriber, one is installed that writes
    /// warnings (MuJoCo's among them) to standard error; `RUST_LOG` chooses what else it shows.
    ///
    /// # Errors
    ///
    /// Composition and configuration errors, each naming its place;
    /// [`RuntimeError::Unsupported`] listing every component that cannot run in the selected
    /// environment; the backend's error.
    pub fn build(mut self) -> Result<Platform, RuntimeError> {
        report_warnings();
        let world = self.world.ok_or(RuntimeError::NoWorld)?;
        let settings = self.config.settings(DEFAULT_ENVIRONMENT);
        for environment in self.config.environments() {
            if !self.backends.contains_key(environment) {
                let hint = did_you_mean(environment, self.backends.keys().copied());
                return Err(config_error(format!(
                    "[environments.{environment}] names no known environment{hint}"
                )));
            }
        }
        let Some((environment, factory)) =
            self.backends.remove_entry(settings.environment.as_str())
        else {
            return Err(RuntimeError::NoBackend {
                environment: settings.environment.clone(),
                available: self.backends.keys().copied().collect::<Vec<_>>().join(", "),
            });
        };
        let platform = settings.platform_settings()?;
        let behaviour = defaulted(&self.behaviour_defaults, &settings)?;
        let composition = match world {
            World::Type(world) => compose_configured(world, &settings)?,
            World::Declared(world) => compose_declaration(*world, &settings)?,
        };
        for path in settings.interfaces.keys() {
            if composition.instance(path).is_none() {
                let paths = composition.instances.iter().map(|i| i.path.as_str());
                return Err(ConfigError {
                    origin: settings.origins.describe_table("interfaces", path),
                    message: format!(
                        "[interfaces.\"{path}\"] names no component{}",
                        did_you_mean_or_list(path, paths)
                    ),
                }
                .into());
            }
        }
        check_support(&composition, environment)?;
        let mut plugins = std::mem::take(&mut self.plugins);
        for name in settings.plugins.keys() {
            let factory = self.plugin_factories.get(name).ok_or_else(|| ConfigError {
                origin: settings.origins.describe_table("plugins", name),
                message: format!(
                    "[plugins.{name}] names no registered plugin{}",
                    did_you_mean_or_list(name, self.plugin_factories.keys().map(String::as_str))
                ),
            })?;
            plugins.push(factory(&settings, name)?);
        }
        one_writer_per_file(&plugins)?;
        check_plugin_support(&plugins, environment)?;
        let backend = factory(&composition, &settings).map_err(|source| RuntimeError::Backend {
            environment: environment.to_owned(),
            source,
        })?;
        Ok(Platform::new(Prepared {
            environment,
            backend,
            composition,
            settings,
            platform,
            behaviour,
            plugins,
            behaviours: self.behaviours,
            stop: self.stop,
            ctrl_c: self.ctrl_c,
        }))
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

/// Every component with interfaces must have one for `environment`.
fn check_support(composition: &Composition, environment: &str) -> Result<(), RuntimeError> {
    let components: Vec<Unsupported> = composition
        .instances
        .iter()
        .filter_map(|instance| {
            let supports = instance.component.environments();
            (!supports.is_empty() && !supports.contains(&environment)).then(|| Unsupported {
                path: instance.path.clone(),
                type_name: instance.component.type_name(),
                supports,
                added_by: instance.component.unavailable(environment),
            })
        })
        .collect();
    if components.is_empty() {
        Ok(())
    } else {
        Err(RuntimeError::Unsupported {
            environment: environment.to_owned(),
            components,
        })
    }
}

/// Every plugin that names its environments must name `environment`.
fn check_plugin_support(
    plugins: &[Box<dyn Plugin>],
    environment: &str,
) -> Result<(), RuntimeError> {
    for plugin in plugins {
        let supports = plugin.environments();
        if !supports.is_empty() && !supports.contains(&environment) {
            return Err(RuntimeError::PluginUnsupported {
                plugin: plugin.name(),
                environment: environment.to_owned(),
                supports,
            });
        }
    }
    Ok(())
}

fn config_error(message: String) -> RuntimeError {
    ConfigError {
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

/// The behaviour's settings: its defaults, overlaid with the run's `[behaviour]` values, each of
/// its default's type; an unknown key or a wrong type names where it was set.
fn defaulted(defaults: &Config, settings: &Settings) -> Result<Config, RuntimeError> {
    let mut config = defaults.clone();
    for (key, value) in settings.behaviour.iter() {
        let value = typed(defaults, key, value.clone()).map_err(|message| ConfigError {
            origin: settings.origins.describe("behaviour", "", key),
            message: format!("[behaviour] {message}"),
        })?;
        config.set(key, value);
    }
    Ok(config)
}

/// Refuses plugins that would write the same file (the second would overwrite or interleave
/// the first's), naming both.
fn one_writer_per_file(plugins: &[Box<dyn Plugin>]) -> Result<(), RuntimeError> {
    let mut writers: BTreeMap<std::path::PathBuf, String> = BTreeMap::new();
    for plugin in plugins {
        for file in plugin.writes() {
            let same = same_file_key(&file);
            if let Some(other) = writers.get(&same) {
                return Err(config_error(format!(
                    "{other} and {} would both write {}: give each its own file",
                    plugin.name(),
                    file.display()
                )));
            }
            writers.insert(same, plugin.name());
        }
    }
    Ok(())
}

/// `file` as one path for every way of writing it: absolute, the links of its longest existing
/// part resolved, and the `.` and `..` of the rest (folders a recorder will make) applied.
fn same_file_key(file: &std::path::Path) -> std::path::PathBuf {
    use std::path::Component;
    let absolute = std::path::absolute(file).unwrap_or_else(|_| file.to_owned());
    let components: Vec<Component<'_>> = absolute.components().collect();
    for existing in (1..=components.len()).rev() {
        let prefix: std::path::PathBuf = components[..existing].iter().collect();
        let Ok(mut key) = prefix.canonicalize() else {
            continue;
        };
        for component in &components[existing..] {
            match component {
                Component::ParentDir => {
                    key.pop();
                }
                Component::Normal(name) => key.push(name),
                Component::CurDir | Component::RootDir | Component::Prefix(_) => {}
            }
        }
        return key;
    }
    absolute
}
