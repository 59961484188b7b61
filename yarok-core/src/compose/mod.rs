//! Composition: component templates → one MJCF world.
//!
//! A component is a type implementing [`Component`]; its [`Declaration`] gives its tag, an
//! optional base it `extends`, the component types usable as tags in its template, typed config
//! defaults and the template itself. [`compose`] expands the world's template — `{expr}` in any
//! attribute, `if="…"`, `<if the="…">`, `<for each="…" as="…">` in every section, in document
//! order — instantiates the components it names, namespaces every name by component path and
//! merges everything into one [`Composition`].
//!
//! # Semantics
//!
//! - **Paths and names.** The world is `/`; a component tag `<arm_type name="arm"/>` in it makes
//!   `/arm`; a component tag written inside another component's tag becomes its child
//!   (`/arm/gripper`). Every name a component defines and every reference it writes gets its path
//!   as prefix (`arm/gripper/pad`); the world's names stay unprefixed. A reference may reach into
//!   a sub-component (`gripper/pad`) or, with a leading `/`, name a world object (`/floor`).
//! - **Defaults.** A component's top-level `<default>` becomes its own class `<path>/main`, given
//!   (as `childclass` or `class`) to its top-level elements, so two copies never clash. Classes
//!   still nest inside the world's `<default>`, so world-wide defaults reach attributes a
//!   component's defaults leave unset, as in MuJoCo.
//! - **Nesting.** Elements written inside a component tag go where the tag was, or with
//!   `parent="body"` into that body of the component.
//! - **Sections.** Sub-components' `asset`, `default`, `actuator`, `sensor`, `tendon`, `equality`,
//!   `contact`, `custom`, `deformable`, `extension` merge into the world. `compiler`, `option`,
//!   `size`, `visual` and `statistic` merge attribute by attribute; differing values are an error
//!   naming both components (an unset `compiler/@angle` counts as MuJoCo's `degree`).
//! - **Files.** Relative `file` attributes are resolved against the component's asset folder (and
//!   its `meshdir`/`texturedir`), so components from different folders mix.
//! - **Keyframes.** A component's `<key>` vectors (`qpos`, `qvel`, `ctrl`, `act`) address that
//!   component's own joints and actuators. They are lifted out of the MJCF into
//!   [`Composition::keyframes`]; the MuJoCo backend places them in whole-model vectors.

mod angles;
mod elements;
mod error;
mod expand;
mod files;
mod layout;
mod mount;
mod names;
mod sections;
mod segments;
mod source;
mod typed;

use std::any::{Any, TypeId};
use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;

pub use elements::MJCF_ELEMENTS;
pub use error::{ComposeError, ErrorDetails};
pub use evalexpr::Value;
pub use names::{NameKind, NameMap};
pub use source::SourceLocation;
pub(crate) use typed::typed;

use crate::config::Settings;
use crate::runtime::{Bind, RuntimeError};
use crate::template::xml::Element;

/// A component: a Rust type with an MJCF template.
///
/// # Examples
///
/// ```
/// use yarok_core::compose::{Component, Declaration, compose};
///
/// struct Block;
/// impl Component for Block {
///     fn declaration() -> Declaration {
///         Declaration::new("block")
///             .default("size", 0.05)
///             .template(r#"<mujoco><worldbody>
///                 <body name="body"><freejoint/><geom type="box" size="{size} {size} {size}"/></body>
///             </worldbody></mujoco>"#)
///     }
/// }
///
/// struct Table;
/// impl Component for Table {
///     fn declaration() -> Declaration {
///         Declaration::new("table").uses::<Block>().template(r#"<mujoco><worldbody>
///             <for each="range(2)" as="i">
///               <body name="spot{i}" pos="{i * 0.2} 0 0.5"><block name="block{i}" size="0.03"/></body>
///             </for>
///         </worldbody></mujoco>"#)
///     }
/// }
///
/// let world = compose::<Table>()?;
/// let xml = world.to_xml();
/// assert!(xml.contains(r#"<body name="block1/body">"#));
/// assert!(xml.contains(r#"size="0.03 0.03 0.03""#));
/// assert_eq!(world.instance("/block0").unwrap().names.len(), 1);
/// # Ok::<(), yarok_core::compose::ComposeError>(())
/// ```
pub trait Component: 'static {
    /// What the component is: tag, template, defaults, sub-components.
    fn declaration() -> Declaration;

    /// Makes the handle behaviours use, for the environment [`Bind::environment`] names:
    /// resolve names to indices, register per-tick steps, reach the backend.
    ///
    /// The default says the component has no run-time interface (worlds, props).
    ///
    /// # Errors
    ///
    /// [`RuntimeError::NoInterface`] when the component cannot run in this environment, or any
    /// binding error.
    fn bind(_bind: &mut Bind<'_>) -> Result<Self, RuntimeError>
    where
        Self: Sized,
    {
        Err(RuntimeError::NoHandle {
            path: String::new(),
        })
    }
}

/// A component type, as a value.
#[derive(Clone, Copy)]
pub struct ComponentType {
    type_id: TypeId,
    type_name: &'static str,
    declaration: fn() -> Declaration,
    bind: fn(&mut Bind<'_>) -> Result<Box<dyn Any>, RuntimeError>,
}

impl ComponentType {
    /// The component type `C`.
    pub fn of<C: Component>() -> Self {
        Self {
            type_id: TypeId::of::<C>(),
            type_name: std::any::type_name::<C>(),
            declaration: C::declaration,
            bind: |bind| C::bind(bind).map(|handle| Box::new(handle) as Box<dyn Any>),
        }
    }

    /// The Rust type's name.
    pub fn type_name(&self) -> &'static str {
        self.type_name
    }

    /// The `TypeId` of the component's Rust type.
    pub fn type_id(&self) -> TypeId {
        self.type_id
    }

    pub(crate) fn bind(&self, bind: &mut Bind<'_>) -> Result<Box<dyn Any>, RuntimeError> {
        (self.bind)(bind)
    }

    /// The component's declaration.
    pub fn declaration(&self) -> Declaration {
        (self.declaration)()
    }
}

impl fmt::Debug for ComponentType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.type_name)
    }
}

/// Where a template comes from.
#[derive(Debug, Clone)]
enum Source {
    Inline(String),
    File(PathBuf),
}

/// What a component declares; built with the methods below.
#[derive(Debug, Clone)]
pub struct Declaration {
    tag: String,
    extends: Option<ComponentType>,
    components: Vec<ComponentType>,
    defaults: Config,
    source: Option<Source>,
    asset_dir: Option<PathBuf>,
    verbatim: bool,
}

impl Declaration {
    /// A component used as `<tag name="…"/>` in other templates.
    pub fn new(tag: impl Into<String>) -> Self {
        Self {
            tag: tag.into(),
            extends: None,
            components: Vec::new(),
            defaults: Config::default(),
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

    /// A config default, visible in the template as a variable and overridable per instance.
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

/// Config values: name → value, in the order they were set.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Config {
    entries: Vec<(String, Value)>,
}

impl Config {
    /// The value of `key`.
    pub fn get(&self, key: &str) -> Option<&Value> {
        self.entries.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }

    /// Sets `key`, keeping its place when it exists.
    pub fn set(&mut self, key: &str, value: Value) {
        match self.entries.iter_mut().find(|(k, _)| k == key) {
            Some(entry) => entry.1 = value,
            None => self.entries.push((key.to_owned(), value)),
        }
    }

    /// Every `(key, value)` in order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &Value)> {
        self.entries.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// Every key.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|(k, _)| k.as_str())
    }
}

impl<K: Into<String>, V: IntoValue, const N: usize> From<[(K, V); N]> for Config {
    fn from(entries: [(K, V); N]) -> Self {
        let mut config = Config::default();
        for (key, value) in entries {
            config.set(&key.into(), value.into_value());
        }
        config
    }
}

/// Rust values usable as config values: numbers, booleans, strings and lists of them.
pub trait IntoValue {
    /// The template value.
    fn into_value(self) -> Value;
}

impl IntoValue for Value {
    fn into_value(self) -> Value {
        self
    }
}

macro_rules! into_value {
    ($($rust:ty => $variant:ident as $as:ty),* $(,)?) => {$(
        impl IntoValue for $rust {
            fn into_value(self) -> Value {
                Value::$variant(self as $as)
            }
        }
    )*};
}

into_value!(i32 => Int as i64, i64 => Int as i64, u32 => Int as i64, f32 => Float as f64, f64 => Float as f64);

impl IntoValue for bool {
    fn into_value(self) -> Value {
        Value::Boolean(self)
    }
}

impl IntoValue for &str {
    fn into_value(self) -> Value {
        Value::String(self.to_owned())
    }
}

impl IntoValue for String {
    fn into_value(self) -> Value {
        Value::String(self)
    }
}

impl<T: IntoValue> IntoValue for Vec<T> {
    fn into_value(self) -> Value {
        Value::Tuple(self.into_iter().map(IntoValue::into_value).collect())
    }
}

impl<T: IntoValue, const N: usize> IntoValue for [T; N] {
    fn into_value(self) -> Value {
        Value::Tuple(self.into_iter().map(IntoValue::into_value).collect())
    }
}

/// One component in the composed world.
#[derive(Debug, Clone)]
pub struct Instance {
    /// `/`, `/arm`, `/arm/gripper`.
    pub path: String,
    /// The component's tag.
    pub tag: String,
    /// The component's Rust type.
    pub component: ComponentType,
    /// Its config after defaults, tag attributes and overrides.
    pub config: Config,
    /// Its names: local → name in the composed model.
    pub names: NameMap,
    /// Indices of its joints among the model's joints, in MuJoCo's order.
    pub joints: Vec<usize>,
    /// Indices of its actuators among the model's actuators.
    pub actuators: Vec<usize>,
}

/// A keyframe a component declared, in its own terms.
#[derive(Debug, Clone, PartialEq)]
pub struct ComponentKeyframe {
    /// Path of the component that declared it.
    pub component: String,
    /// The keyframe's name in the composed model.
    pub name: String,
    /// Its attributes (`time`, `qpos`, `qvel`, `ctrl`, `act`), vectors over the component's own
    /// joints and actuators, and `from`: the composed names of keyframes it combines
    /// (`from="left/home right/home"`), applied in order before its own vectors.
    pub attributes: Vec<(String, String)>,
}

/// A composed world: one MJCF document plus what the backends need to bind components to it.
#[derive(Debug, Clone)]
pub struct Composition {
    /// The `<mujoco>` document.
    pub mjcf: Element,
    /// Every component, parents before children (the world first).
    pub instances: Vec<Instance>,
    /// Files the model reads (meshes, textures, height fields), absolute.
    pub assets: Vec<PathBuf>,
    /// Keyframes lifted out of the MJCF, to be placed by the backend.
    pub keyframes: Vec<ComponentKeyframe>,
    /// Whether joint and actuator indices are known (no `composite`, `flexcomp`, `replicate`,
    /// `attach` generate hidden ones).
    pub layout_known: bool,
    /// The templates the world was composed from (file paths, or `<tag> (inline template)`),
    /// indexed by the elements' origin; see [`Composition::source_of_line`].
    pub templates: Vec<String>,
}

impl Composition {
    /// The composed MJCF as text.
    pub fn to_xml(&self) -> String {
        self.mjcf.to_xml()
    }

    /// The component at `path`.
    pub fn instance(&self, path: &str) -> Option<&Instance> {
        self.instances.iter().find(|i| i.path == path)
    }
}

/// Config overrides by component path, applied over defaults and tag attributes.
pub type Overrides = BTreeMap<String, Config>;

/// Composes the world `W` with its defaults.
///
/// # Errors
///
/// [`ComposeError`] naming the component, template, line:column, element, attribute and
/// expression at fault.
pub fn compose<W: Component>() -> Result<Composition, ComposeError> {
    compose_with(ComponentType::of::<W>(), &Overrides::new())
}

/// Composes the world `world` with config `overrides` by component path.
///
/// # Errors
///
/// As [`compose`]; an override for a path that is not composed is an error too.
pub fn compose_with(
    world: ComponentType,
    overrides: &Overrides,
) -> Result<Composition, ComposeError> {
    expand::Composer::new(overrides, None, None).compose(world)
}

/// Composes the world `world` with a run's settings: its component config, and errors in a
/// value name where it was set (the file and key, or the `--set` argument).
///
/// # Errors
///
/// As [`compose_with`].
pub fn compose_configured(
    world: ComponentType,
    settings: &Settings,
) -> Result<Composition, ComposeError> {
    expand::Composer::new(&settings.components, Some(&settings.origins), None).compose(world)
}

/// Composes a world declared at run time, e.g. from a template file named on a command line,
/// with a run's settings (see [`compose_configured`]).
///
/// # Errors
///
/// As [`compose_with`].
pub fn compose_declaration(
    world: Declaration,
    settings: &Settings,
) -> Result<Composition, ComposeError> {
    let world_type = ComponentType {
        type_name: "run-time world",
        ..ComponentType::of::<RuntimeWorld>()
    };
    expand::Composer::new(&settings.components, Some(&settings.origins), Some(world))
        .compose(world_type)
}

/// Stands for a world declared at run time; its declaration is handed to the composer.
struct RuntimeWorld;

impl Component for RuntimeWorld {
    fn declaration() -> Declaration {
        Declaration::new("world")
    }
}
