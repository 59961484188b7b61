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
mod limits;
mod loader;
mod mount;
mod namespace;
mod sections;
mod segments;
mod source;

use std::path::PathBuf;

pub use elements::MJCF_ELEMENTS;
pub use error::{ComposeError, ErrorDetails};
pub use source::SourceLocation;

use crate::component::{Component, ComponentType, Declaration, NameMap};
use crate::config::Settings;
use crate::template::xml::Element;
use crate::value::{Config, Overrides};

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
    let world_type = ComponentType::of::<RuntimeWorld>().with_name("run-time world");
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
