//! [`Exports`]: what an extension module built with [`module!`](crate::module) offers Python
//! beside yarok's bundled worlds — worlds of your own crate, opened by their tags, and
//! components your template files use.

use std::sync::OnceLock;

use yarok::components::template_world;
use yarok::core::component::{Component, ComponentType, Declaration};

/// The worlds and components of your own crate an extension module exports to Python:
/// `Exports::new().world::<Showroom>().component::<Turntable>()`, given to
/// [`module!`](crate::module) (`examples/own_crate/py` is built and tested by CI).
#[derive(Clone, Default)]
pub struct Exports {
    worlds: Vec<ComponentType>,
    components: Vec<ComponentType>,
}

impl std::fmt::Debug for Exports {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names = |types: &[ComponentType]| -> Vec<&'static str> {
            types.iter().map(ComponentType::type_name).collect()
        };
        f.debug_struct("Exports")
            .field("worlds", &names(&self.worlds))
            .field("components", &names(&self.components))
            .finish()
    }
}

impl Exports {
    /// Nothing beyond the bundled worlds and components.
    pub fn new() -> Self {
        Self::default()
    }

    /// The world `W`, opened from Python by its tag (`World("showroom")`); template files may
    /// use it too.
    pub fn world<W: Component>(mut self) -> Self {
        self.worlds.push(ComponentType::of::<W>());
        self
    }

    /// The component `C`, used by its tag in template files opened from Python
    /// (`World("my_world.xml")`).
    pub fn component<C: Component>(mut self) -> Self {
        self.components.push(ComponentType::of::<C>());
        self
    }

    /// The tags of the exported worlds, in the order given.
    pub fn world_tags(&self) -> Vec<String> {
        self.worlds
            .iter()
            .map(|world| world.declaration().tag().to_owned())
            .collect()
    }

    /// The exported world tagged `tag`.
    pub(crate) fn world_tagged(&self, tag: &str) -> Option<ComponentType> {
        self.worlds
            .iter()
            .copied()
            .find(|world| world.declaration().tag() == tag)
    }

    /// The world of the template file `path`, using the bundled components and the exported
    /// ones by their tags.
    pub(crate) fn template_world(&self, path: &str) -> Declaration {
        self.worlds
            .iter()
            .chain(&self.components)
            .fold(template_world(path), |world, &component| {
                world.uses_type(component)
            })
    }
}

static EXPORTED: OnceLock<Exports> = OnceLock::new();

/// Records what this extension module exports; refused if it was recorded already (a module
/// initialised twice in one process).
pub(crate) fn record(exports: Exports) -> Result<(), String> {
    EXPORTED
        .set(exports)
        .map_err(|_| "this extension module was initialised twice".to_owned())
}

/// What this extension module exports (nothing before it is initialised).
pub(crate) fn exported() -> &'static Exports {
    EXPORTED.get_or_init(Exports::new)
}
