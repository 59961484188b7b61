//! Run configuration: one tree in layers — component defaults < run settings < the selected
//! environment's settings < settings from code and the command line.
//!
//! ```toml
//! environment = "sim"              # which backend: "sim", "real", "mock"
//!
//! [platform]
//! realtime = true                  # pace simulation to the wall clock (for a viewer)
//!
//! [components."/tower"]            # component config, by component path
//! rows = 4
//!
//! [interfaces."/printer"]          # interface settings, by component path
//! port = "/dev/ttyUSB0"
//!
//! [behaviour]                      # the behaviour's own settings
//! poses = 3
//!
//! [plugins.recorder]               # plugins to create, by registered name
//! every = 10
//!
//! [environments.real.components."/printer"]
//! speed = 0.5                      # only when environment = "real"
//! ```

use std::collections::BTreeMap;
use std::path::Path;

use serde::de::DeserializeOwned;

use crate::suggest::did_you_mean;
use crate::value::{Config, Overrides, Value};

/// A run configuration could not be read.
#[derive(Clone, PartialEq, Eq, thiserror::Error)]
#[error("{origin}: {message}")]
pub struct ConfigError {
    /// The file, `<string>`, or `--set`.
    pub origin: String,
    /// What is wrong, with line and column for TOML syntax errors.
    pub message: String,
}

/// Where each value of a run configuration was set: the file and key, or the `--set`
/// argument, by section (`components`, `interfaces`, `plugins`, `behaviour`, `platform`), path
/// (component path or plugin name; empty for `behaviour` and `platform`) and key.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ConfigOrigins(BTreeMap<(String, String, String), String>);

impl ConfigOrigins {
    /// Where `section` / `path` / `key` was set, if it was.
    pub fn of(&self, section: &str, path: &str, key: &str) -> Option<&str> {
        self.0
            .get(&(section.to_owned(), path.to_owned(), key.to_owned()))
            .map(String::as_str)
    }

    /// Where `section` / `path` / `key` was set, or "run configuration" when unknown.
    pub fn describe(&self, section: &str, path: &str, key: &str) -> String {
        self.of(section, path, key)
            .unwrap_or("run configuration")
            .to_owned()
    }

    /// Where the first key of `section` / `path` (a plugin's name, a component's path) was
    /// set, or "run configuration" when unknown: for errors about the whole table.
    pub fn describe_table(&self, section: &str, path: &str) -> String {
        self.0
            .iter()
            .find(|((s, p, _), _)| s == section && p == path)
            .map_or_else(
                || "run configuration".to_owned(),
                |(_, origin)| origin.clone(),
            )
    }

    fn record(&mut self, section: &str, path: &str, key: &str, origin: String) {
        self.0.insert(
            (section.to_owned(), path.to_owned(), key.to_owned()),
            origin,
        );
    }

    fn merge(&mut self, other: ConfigOrigins) {
        self.0.extend(other.0);
    }
}

crate::debug_as_report!(ConfigError);

/// The sections of one layer.
#[derive(Debug, Clone, Default, PartialEq)]
struct Layer {
    components: BTreeMap<String, Config>,
    interfaces: BTreeMap<String, Config>,
    behaviour: Config,
    plugins: BTreeMap<String, Config>,
    platform: Config,
    origins: ConfigOrigins,
}

const SECTIONS: [&str; 5] = [
    "components",
    "interfaces",
    "behaviour",
    "plugins",
    "platform",
];

impl Layer {
    fn merge(&mut self, other: Layer) {
        let by_path = |mine: &mut BTreeMap<String, Config>, theirs: BTreeMap<String, Config>| {
            for (path, config) in theirs {
                mine.entry(path).or_default().merge(&config);
            }
        };
        by_path(&mut self.components, other.components);
        by_path(&mut self.interfaces, other.interfaces);
        by_path(&mut self.plugins, other.plugins);
        self.behaviour.merge(&other.behaviour);
        self.platform.merge(&other.platform);
        self.origins.merge(other.origins);
    }
}

/// A run configuration: settings for every environment, and the one selected.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunConfig {
    environment: Option<String>,
    base: Layer,
    environments: BTreeMap<String, Layer>,
}

/// The settings in force for one run: the base layer overlaid with the selected environment's.
/// The default is an empty configuration for environment `sim`.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// The selected environment.
    pub environment: String,
    /// Component config by path.
    pub components: Overrides,
    /// Interface settings by path.
    pub interfaces: BTreeMap<String, Config>,
    /// The behaviour's settings.
    pub behaviour: Config,
    /// Plugins to create, by registered name, with their settings.
    pub plugins: BTreeMap<String, Config>,
    /// Platform settings (`realtime`, `tick_hz`, …).
    pub platform: Config,
    /// Where each of these values was set.
    pub origins: ConfigOrigins,
}

impl Default for Settings {
    fn default() -> Self {
        RunConfig::default().settings("sim")
    }
}

impl Settings {
    /// The `[platform]` settings, typed.
    ///
    /// # Errors
    ///
    /// [`ConfigError`] naming where an unknown key or a value of the wrong type was set.
    pub fn platform_settings(&self) -> Result<PlatformSettings, ConfigError> {
        self.read("platform", "", &self.platform)
    }

    /// The settings of plugin `name` (`[plugins.name]`), read into `T`.
    ///
    /// # Errors
    ///
    /// As [`Settings::platform_settings`].
    pub fn plugin_settings<T: DeserializeOwned>(&self, name: &str) -> Result<T, ConfigError> {
        let empty = Config::default();
        let config = self.plugins.get(name).unwrap_or(&empty);
        self.read("plugins", name, config)
    }

    fn read<T: DeserializeOwned>(
        &self,
        section: &str,
        path: &str,
        config: &Config,
    ) -> Result<T, ConfigError> {
        config.deserialize().map_err(|error| {
            let origin = match &error.key {
                Some(key) => self.origins.describe(section, path, key),
                None => "run configuration".to_owned(),
            };
            let place = if path.is_empty() {
                format!("[{section}]")
            } else {
                format!("[{section}.{path}]")
            };
            ConfigError {
                origin,
                message: format!("{place} {error}"),
            }
        })
    }
}

/// The `[platform]` section.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default)]
#[non_exhaustive]
pub struct PlatformSettings {
    /// Pace simulated ticks to the wall clock (for watching); hardware always is.
    pub realtime: bool,
    /// Ticks per second on hardware.
    pub tick_hz: f64,
    /// The seed every component's random numbers derive from (see [`PlatformSettings::seed_for`]).
    pub seed: u64,
    /// Where compiled models are kept between runs.
    pub model_cache: ModelCache,
    /// Which share of its work this run does (`"I/N"`), for runs split over machines.
    pub shard: Shard,
}

impl Default for PlatformSettings {
    fn default() -> Self {
        Self {
            realtime: false,
            tick_hz: 100.0,
            seed: 0,
            model_cache: ModelCache::Enabled(true),
            shard: Shard::WHOLE,
        }
    }
}

/// Which share of a run's work — its parameter grid, its episodes — this run does
/// (`[platform] shard = "I/N"`, `yarok run … --shard I/N`): item `k` of the work belongs to
/// shard `k mod N` (0-based, as Slurm array and Kubernetes indexed-job indices count), so the N
/// shards of a run do, between them, exactly what the whole run does. Behaviours read it with
/// [`Pl::shard`](crate::runtime::Pl::shard).
///
/// # Examples
///
/// ```
/// use yarok_core::config::Shard;
///
/// let shard: Shard = "1/3".parse()?;
/// let mine: Vec<(usize, char)> = shard.select("abcdefg".chars());
/// assert_eq!(mine, [(1, 'b'), (4, 'e')]);
/// # Ok::<(), String>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(try_from = "String")]
pub struct Shard {
    /// This shard's number, from 0.
    pub index: usize,
    /// How many shards the run is split into.
    pub count: usize,
}

impl Shard {
    /// The whole run: `0/1`.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Whether item `item` of the work is this shard's.
    pub fn owns(&self, item: usize) -> bool {
        item % self.count == self.index
    }

    /// This shard's items of `items`, each with its number in the whole run.
    pub fn select<T>(&self, items: impl IntoIterator<Item = T>) -> Vec<(usize, T)> {
        items
            .into_iter()
            .enumerate()
            .filter(|(item, _)| self.owns(*item))
            .collect()
    }

    /// Whether this is the whole run.
    pub fn is_whole(&self) -> bool {
        self.count == 1
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl std::str::FromStr for Shard {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let malformed = || format!("{text:?}: expected I/N with 0 ≤ I < N, as \"2/8\"");
        let (index, count) = text.split_once('/').ok_or_else(malformed)?;
        let shard = Shard {
            index: index.trim().parse().map_err(|_| malformed())?,
            count: count.trim().parse().map_err(|_| malformed())?,
        };
        if shard.index >= shard.count {
            return Err(malformed());
        }
        Ok(shard)
    }
}

impl TryFrom<String> for Shard {
    type Error = String;

    fn try_from(text: String) -> Result<Self, String> {
        text.parse()
    }
}

/// Where compiled models are kept between runs (`[platform] model_cache`): `true` (the default)
/// in the user's cache folder — `$YAROK_CACHE_DIR/models`, else `$XDG_CACHE_HOME/yarok/models`,
/// else `~/.cache/yarok/models` — `false` nowhere, or a folder's path (`~/` is the home folder).
/// An empty path, or `"true"`/`"yes"`-like words in quotes, are errors, not folders.
#[derive(Debug, Clone, PartialEq)]
pub enum ModelCache {
    /// In the user's cache folder, or nowhere.
    Enabled(bool),
    /// In this folder.
    Folder(std::path::PathBuf),
}

impl<'de> serde::Deserialize<'de> for ModelCache {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = ModelCache;

            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("true, false or a folder's path")
            }

            fn visit_bool<E: serde::de::Error>(self, enabled: bool) -> Result<ModelCache, E> {
                Ok(ModelCache::Enabled(enabled))
            }

            fn visit_str<E: serde::de::Error>(self, path: &str) -> Result<ModelCache, E> {
                ModelCache::folder_named(path).map_err(E::custom)
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

impl ModelCache {
    /// The cache in the folder `path` names (`~/` expanded).
    fn folder_named(path: &str) -> Result<Self, String> {
        let word = path.trim().to_ascii_lowercase();
        if word.is_empty() {
            return Err("an empty path: give a folder, or true or false".into());
        }
        if ["true", "false", "yes", "no", "on", "off"].contains(&word.as_str()) {
            return Err(format!(
                "{path:?} is a word in quotes: write true or false without them, or a folder's \
                 path"
            ));
        }
        let home = || {
            std::env::var_os("HOME")
                .filter(|home| !home.is_empty())
                .map(std::path::PathBuf::from)
                .ok_or_else(|| format!("{path:?} starts with ~, but HOME is not set"))
        };
        Ok(ModelCache::Folder(match path.strip_prefix('~') {
            Some("") => home()?,
            Some(rest) if rest.starts_with('/') => home()?.join(&rest[1..]),
            _ => std::path::PathBuf::from(path),
        }))
    }

    /// The folder, if models are kept.
    pub fn folder(&self) -> Option<std::path::PathBuf> {
        match self {
            ModelCache::Enabled(false) => None,
            ModelCache::Folder(folder) => Some(folder.clone()),
            ModelCache::Enabled(true) => {
                let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty());
                let yarok = var("YAROK_CACHE_DIR")
                    .map(std::path::PathBuf::from)
                    .or_else(|| {
                        var("XDG_CACHE_HOME").map(|c| std::path::Path::new(&c).join("yarok"))
                    })
                    .or_else(|| {
                        var("HOME").map(|h| std::path::Path::new(&h).join(".cache/yarok"))
                    })?;
                Some(yarok.join("models"))
            }
        }
    }
}

impl PlatformSettings {
    /// The seed of the component at `path`: the platform seed mixed with the path, so the same
    /// configuration gives the same numbers and two components differ.
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_core::config::PlatformSettings;
    ///
    /// let settings = PlatformSettings::default();
    /// assert_eq!(settings.seed_for("/left"), settings.seed_for("/left"));
    /// assert_ne!(settings.seed_for("/left"), settings.seed_for("/right"));
    /// ```
    pub fn seed_for(&self, path: &str) -> u64 {
        // FNV-1a over the path, then SplitMix64's finaliser over it and the seed.
        let hash = path.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |hash, byte| {
            (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3)
        });
        let mut z = (hash ^ self.seed).wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
}

impl RunConfig {
    /// Reads TOML text; `origin` names it in errors.
    ///
    /// # Errors
    ///
    /// [`ConfigError`] for TOML syntax (with line and column), unknown sections (with a
    /// suggestion) and values of unsupported types.
    pub fn from_toml(text: &str, origin: &str) -> Result<Self, ConfigError> {
        let error = |message: String| ConfigError {
            origin: origin.to_owned(),
            message,
        };
        let table: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| error(e.to_string().trim().to_owned()))?;
        let mut config = RunConfig::default();
        for (key, value) in table {
            match key.as_str() {
                "environment" => match value {
                    toml::Value::String(name) => config.environment = Some(name),
                    other => {
                        return Err(error(format!(
                            "`environment` must be a string, not {}",
                            other.type_str()
                        )));
                    }
                },
                "environments" => {
                    let toml::Value::Table(environments) = value else {
                        return Err(error(
                            "`environments` must be a table of environments".into(),
                        ));
                    };
                    for (name, layer) in environments {
                        let toml::Value::Table(layer) = layer else {
                            return Err(error(format!("`environments.{name}` must be a table")));
                        };
                        let layer = read_layer(layer, &format!("environments.{name}."), origin)
                            .map_err(error)?;
                        config.environments.insert(name, layer);
                    }
                }
                _ => {
                    let mut single = toml::Table::new();
                    single.insert(key, value);
                    config
                        .base
                        .merge(read_layer(single, "", origin).map_err(error)?);
                }
            }
        }
        Ok(config)
    }

    /// Reads a TOML file.
    ///
    /// # Errors
    ///
    /// As [`RunConfig::from_toml`], or when the file cannot be read.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, ConfigError> {
        let path = path.as_ref();
        let text = crate::bounded::read_text(path, crate::bounded::CONFIG_LIMIT).map_err(|e| {
            ConfigError {
                origin: path.display().to_string(),
                message: format!("cannot read: {e}"),
            }
        })?;
        Self::from_toml(&text, &path.display().to_string())
    }

    /// Overlays `other`: its values win, key by key.
    pub fn merge(&mut self, other: RunConfig) {
        if other.environment.is_some() {
            self.environment = other.environment;
        }
        self.base.merge(other.base);
        for (name, layer) in other.environments {
            self.environments.entry(name).or_default().merge(layer);
        }
    }

    /// Selects the environment.
    pub fn set_environment(&mut self, environment: &str) {
        self.environment = Some(environment.to_owned());
    }

    /// Sets one value, as the command line's `--set` does: `/path/key=value` for a component
    /// (`/key=value` or just `key=value` for the world), `interfaces/path/key=value`, `behaviour/key=value`,
    /// `platform/key=value`, `plugins/name/key=value`. The value is read as TOML (`0.5`, `true`,
    /// `[1, 2]`, `"text"`), and as a plain string when it is not valid TOML.
    ///
    /// # Errors
    ///
    /// [`ConfigError`] when the assignment is malformed.
    pub fn set(&mut self, assignment: &str) -> Result<(), ConfigError> {
        let error = |message: String| ConfigError {
            origin: format!("--set {assignment}"),
            message,
        };
        let (target, text) = assignment
            .split_once('=')
            .ok_or_else(|| error("expected TARGET=VALUE".into()))?;
        let value = Value::from_text(text);
        // A bare `key=value` sets the world's key.
        let (path, key) = target.rsplit_once('/').unwrap_or(("", target));
        if key.is_empty() {
            return Err(error("the key is empty".into()));
        }
        let layer = &mut self.base;
        let (section, owner, config) = match path
            .split_once('/')
            .map_or((path, ""), |(section, rest)| (section, rest))
        {
            ("", _) => {
                let owner = if path.is_empty() { "/" } else { path }.to_owned();
                let config = layer.components.entry(owner.clone()).or_default();
                ("components", owner, config)
            }
            ("interfaces", rest) => {
                let owner = format!("/{rest}");
                let config = layer.interfaces.entry(owner.clone()).or_default();
                ("interfaces", owner, config)
            }
            ("plugins", name) if !name.is_empty() => {
                let config = layer.plugins.entry(name.to_owned()).or_default();
                ("plugins", name.to_owned(), config)
            }
            ("behaviour", "") => ("behaviour", String::new(), &mut layer.behaviour),
            ("platform", "") => ("platform", String::new(), &mut layer.platform),
            (section, _) => {
                let hint = did_you_mean(section, SECTIONS);
                return Err(error(format!("unknown target `{section}`{hint}")));
            }
        };
        config.set(key, value);
        layer
            .origins
            .record(section, &owner, key, format!("--set {assignment}"));
        Ok(())
    }

    /// The settings in force for the selected environment (`default_environment` when none is).
    pub fn settings(&self, default_environment: &str) -> Settings {
        let environment = self
            .environment
            .clone()
            .unwrap_or_else(|| default_environment.to_owned());
        let mut layer = self.base.clone();
        if let Some(overlay) = self.environments.get(&environment) {
            layer.merge(overlay.clone());
        }
        Settings {
            environment,
            components: layer.components,
            interfaces: layer.interfaces,
            behaviour: layer.behaviour,
            plugins: layer.plugins,
            platform: layer.platform,
            origins: layer.origins,
        }
    }

    /// The environments the configuration has sections for.
    pub fn environments(&self) -> impl Iterator<Item = &str> {
        self.environments.keys().map(String::as_str)
    }
}

/// Reads the sections of one layer from `origin`; `prefix` is where the layer is in the file
/// (`environments.real.`).
fn read_layer(table: toml::Table, prefix: &str, origin: &str) -> Result<Layer, String> {
    let mut layer = Layer::default();
    for (section, value) in table {
        if !SECTIONS.contains(&section.as_str()) {
            let mut known = SECTIONS.to_vec();
            if prefix.is_empty() {
                known.extend(["environment", "environments"]);
            }
            return Err(format!(
                "unknown section `{prefix}{section}`{}",
                did_you_mean(&section, known)
            ));
        }
        let toml::Value::Table(entries) = value else {
            return Err(format!("`{prefix}{section}` must be a table"));
        };
        let mut reader = Reader {
            origin,
            origins: &mut layer.origins,
            section: &section,
            prefix,
        };
        match section.as_str() {
            "components" => layer.components = reader.named(entries)?,
            "interfaces" => layer.interfaces = reader.named(entries)?,
            "plugins" => layer.plugins = reader.named(entries)?,
            "behaviour" => layer.behaviour = reader.config(entries, "")?,
            _ => layer.platform = reader.config(entries, "")?,
        }
    }
    Ok(layer)
}

/// Reads one section's values, noting where each was set.
struct Reader<'a> {
    origin: &'a str,
    origins: &'a mut ConfigOrigins,
    section: &'a str,
    prefix: &'a str,
}

impl Reader<'_> {
    /// A table of configs by component path or plugin name.
    fn named(&mut self, entries: toml::Table) -> Result<BTreeMap<String, Config>, String> {
        let mut named = BTreeMap::new();
        for (name, config) in entries {
            let toml::Value::Table(config) = config else {
                let (prefix, section) = (self.prefix, self.section);
                return Err(format!("`{prefix}{section}.{name:?}` must be a table"));
            };
            let config = self.config(config, &name)?;
            named.insert(name, config);
        }
        Ok(named)
    }

    /// The values of one config table, at `path` (empty for `behaviour` and `platform`).
    fn config(&mut self, table: toml::Table, path: &str) -> Result<Config, String> {
        let mut config = Config::default();
        for (key, value) in table {
            let place = if path.is_empty() {
                format!("{}{}.{key}", self.prefix, self.section)
            } else {
                format!("{}{}.{path:?}.{key}", self.prefix, self.section)
            };
            let value = Value::from_toml(value)
                .ok_or_else(|| format!("`{place}`: tables and dates are not config values"))?;
            self.origins.record(
                self.section,
                path,
                &key,
                format!("{}, key `{place}`", self.origin),
            );
            config.set(&key, value);
        }
        Ok(config)
    }
}
