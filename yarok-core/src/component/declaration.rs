//! [`Declaration`]: what a component is — tag, template, defaults, sub-components.

use std::path::PathBuf;

use super::{Component, ComponentType};
use crate::value::{Config, IntoValue, SettingsError};

/// Where a template comes from.
#[derive(Debug, Clone)]
pub(crate) enum Source {
    Inline(String),
    File(PathBuf),
}

/// What a component declares; built with the methods below.
#[derive(Debug, Clone)]
pub struct Declaration {
    pub(crate) tag: String,
    pub(crate) extends: Option<ComponentType>,
    pub(crate) components: Vec<ComponentType>,
    pub(crate) defaults: Config,
    /// Why [`Declaration::config`]'s struct could not become config values.
    pub(crate) config_error: Option<SettingsError>,
    pub(crate) source: Option<Source>,
    pub(crate) asset_dir: Option<PathBuf>,
    pub(crate) verbatim: bool,
}

impl Declaration {
    /// A component used as `<tag name="…"/>` in other templates.
    pub fn new(tag: impl Into<String>) -> Self {
        Self {
            tag: tag.into(),
            extends: None,
            components: Vec::new(),
            defaults: Config::default(),
            config_error: None,
            source: None,
            asset_dir: None,
            verbatim: false,
        }
    }

    /// Builds on `Base`'s template, defaults and sub-components; this template's content is added
    /// to the base's and may reference the base's names.
    pub fn extends<Base: Component>(mut self) -> Self {
        self.extends = Some(ComponentType::of::<Base>());
        self
    }

    /// Makes `C`'s tag usable in this template.
    pub fn uses<C: Component>(self) -> Self {
        self.uses_type(ComponentType::of::<C>())
    }

    /// Makes a component type's tag usable in this template (for types chosen at run time).
    pub fn uses_type(mut self, component: ComponentType) -> Self {
        self.components.push(component);
        self
    }

    /// The component's config: a serde struct whose fields, with the values given here as
    /// their defaults, are the template's variables, set per instance by tag attributes and
    /// run configurations (checked against these values' types), and read back whole by the
    /// interface with [`Bind::config`](super::Bind::config). Fields hold numbers, booleans,
    /// text, unit enum variants (as their names) and lists of them.
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_core::component::Declaration;
    ///
    /// #[derive(serde::Serialize, serde::Deserialize)]
    /// struct Lamp { brightness: f64, rgb: [u8; 3] }
    ///
    /// let lamp = Declaration::new("lamp")
    ///     .config(Lamp { brightness: 0.5, rgb: [255, 200, 0] })
    ///     .template(r#"<mujoco><worldbody><light diffuse="{rgb[0] / 255 * brightness} 0 0"/></worldbody></mujoco>"#);
    /// ```
    pub fn config(mut self, defaults: impl serde::Serialize) -> Self {
        match Config::from_fields(&defaults) {
            Ok(config) if self.defaults.is_empty() => self.defaults = config,
            Ok(config) => self.defaults.merge(&config),
            Err(error) => self.config_error = Some(error),
        }
        self
    }

    /// One template variable with its default, overridable per instance: for a value no
    /// interface reads (an interface reads its config through [`Declaration::config`]).
    pub fn default(mut self, key: &str, value: impl IntoValue) -> Self {
        self.defaults.set(key, value.into_value());
        self
    }

    /// The template, as MJCF text.
    pub fn template(mut self, mjcf: impl Into<String>) -> Self {
        self.source = Some(Source::Inline(mjcf.into()));
        self
    }

    /// The template, from a file; relative `file=` paths resolve against its folder unless
    /// [`Declaration::asset_dir`] says otherwise.
    pub fn template_file(mut self, path: impl Into<PathBuf>) -> Self {
        self.source = Some(Source::File(path.into()));
        self
    }

    /// Wraps an existing MJCF file (e.g. a MuJoCo Menagerie model) as it is: no template
    /// expressions are evaluated, `<include>`s are inlined, and its assets resolve against its
    /// folder and its own `meshdir`/`texturedir`.
    pub fn mjcf_file(self, path: impl Into<PathBuf>) -> Self {
        Self {
            verbatim: true,
            ..self.template_file(path)
        }
    }

    /// The folder relative `file=` paths resolve against.
    pub fn asset_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.asset_dir = Some(dir.into());
        self
    }

    /// The tag.
    pub fn tag(&self) -> &str {
        &self.tag
    }
}
