//! The template loader: reads a component's template (inline or from a file), parses it,
//! inlines its `<include>`s, and merges it onto the template it `extends`; once per component type.

use std::collections::HashMap;
use std::path::PathBuf;

use super::ComposeError;
use super::error::ErrorDetails;
use super::files::{self, Origin};
use crate::component::{ComponentType, Declaration, Source};
use crate::template::xml::{Element, Position};
use crate::value::Config;

/// A loaded (and, for `extends`, merged) template with what its component declares.
#[derive(Clone)]
pub(super) struct Loaded {
    pub(super) tree: Element,
    pub(super) tag: String,
    pub(super) components: Vec<ComponentType>,
    pub(super) defaults: Config,
    pub(super) verbatim: bool,
}

/// Loads templates, once per component type, remembering where each came from.
pub(super) struct Loader {
    /// Where each template came from, by the elements' `origin`.
    pub(super) origins: Vec<Origin>,
    loaded: HashMap<std::any::TypeId, Loaded>,
    /// Declarations read for their tag before their template is loaded, kept for the load.
    declared: HashMap<std::any::TypeId, Declaration>,
    /// The declaration of a world declared at run time, used for the first component loaded.
    runtime_world: Option<Declaration>,
    /// The component types whose templates are being loaded (`extends` chains), outermost first.
    loading: Vec<ComponentType>,
}

impl Loader {
    pub(super) fn new(runtime_world: Option<Declaration>) -> Self {
        Self {
            origins: Vec::new(),
            loaded: HashMap::new(),
            declared: HashMap::new(),
            runtime_world,
            loading: Vec::new(),
        }
    }

    /// A component type's tag, from its loaded template when there is one.
    pub(super) fn tag_of(&mut self, component: ComponentType) -> String {
        if let Some(loaded) = self.loaded.get(&component.type_id()) {
            return loaded.tag.clone();
        }
        let declared = self.declared.entry(component.type_id());
        declared
            .or_insert_with(|| component.declaration())
            .tag
            .clone()
    }

    pub(super) fn load(
        &mut self,
        component: ComponentType,
        path: &str,
    ) -> Result<Loaded, ComposeError> {
        if let Some(loaded) = self.loaded.get(&component.type_id()) {
            return Ok(loaded.clone());
        }
        let declaration = self
            .runtime_world
            .take()
            .or_else(|| self.declared.remove(&component.type_id()))
            .unwrap_or_else(|| component.declaration());
        let origin = self.origins.len();
        let (text, label, file_dir) = template_text(&declaration, component, path)?;
        let error = |position, message| template_error(path, &label, position, message);
        if let Some(refused) = &declaration.config_error {
            return Err(error(
                None,
                format!(
                    "{} declares a config yarok cannot hold: {refused}",
                    component.type_name()
                ),
            ));
        }
        let document = Element::parse(&text).map_err(|e| error(Some(e.position), e.message))?;
        for stray in &document.stray_text {
            tracing::warn!("{label}:{stray}");
        }
        let mut tree = document.root;
        if tree.name != "mujoco" {
            return Err(error(
                Some(tree.position),
                format!("the root element is <{}>, not <mujoco>", tree.name),
            ));
        }
        let dir = declaration.asset_dir.clone().or(file_dir);
        files::inline_includes(&mut tree, dir.as_deref())
            .map_err(|(position, message)| error(position, message))?;
        set_origin(&mut tree, origin);
        self.origins.push(Origin::new(label.clone(), dir, &tree));
        let mut loaded = Loaded {
            tree,
            tag: declaration.tag.clone(),
            components: declaration.components.clone(),
            defaults: declaration.defaults.clone(),
            verbatim: declaration.verbatim,
        };
        if let Some(base) = declaration.extends {
            loaded = extend(self.load_base(component, base, path, &label)?, loaded);
        }
        self.loaded.insert(component.type_id(), loaded.clone());
        Ok(loaded)
    }

    /// The template `component` (from `label`) extends, refused when the chain comes back to a
    /// template being loaded.
    fn load_base(
        &mut self,
        component: ComponentType,
        base: ComponentType,
        path: &str,
        label: &str,
    ) -> Result<Loaded, ComposeError> {
        self.loading.push(component);
        if self.loading.iter().any(|c| c.type_id() == base.type_id()) {
            let chain: Vec<&str> = self.loading.iter().map(|c| c.type_name()).collect();
            let message = format!(
                "{} extends itself: {} → {}",
                base.type_name(),
                chain.join(" → "),
                base.type_name()
            );
            return Err(template_error(path, label, None, message));
        }
        let loaded = self.load(base, path);
        self.loading.pop();
        loaded
    }
}

/// A declaration's template text, the name errors give it, and the folder of its file.
fn template_text(
    declaration: &Declaration,
    component: ComponentType,
    path: &str,
) -> Result<(String, String, Option<PathBuf>), ComposeError> {
    match &declaration.source {
        Some(Source::Inline(text)) => Ok((
            text.clone(),
            format!("<{}> (inline template)", declaration.tag),
            None,
        )),
        Some(Source::File(file)) => {
            let label = file.display().to_string();
            let text =
                crate::bounded::read_text(file, crate::bounded::TEMPLATE_LIMIT).map_err(|e| {
                    template_error(path, &label, None, format!("cannot read the template: {e}"))
                })?;
            Ok((text, label, file.parent().map(PathBuf::from)))
        }
        None => Err(template_error(
            path,
            &format!("<{}>", declaration.tag),
            None,
            format!("{} declares no template", component.type_name()),
        )),
    }
}

/// An error in the template `template` of the component at `path`.
fn template_error(
    path: &str,
    template: &str,
    position: Option<Position>,
    message: String,
) -> ComposeError {
    ComposeError::from(ErrorDetails {
        component: path.to_owned(),
        template: template.to_owned(),
        position,
        element: None,
        attribute: None,
        expression: None,
        message,
    })
}

/// The base's tree with the extending template's content added; one instance, one prefix.
fn extend(base: Loaded, child: Loaded) -> Loaded {
    let mut tree = base.tree;
    for section in child.tree.children {
        match tree.children.iter_mut().find(|s| s.name == section.name) {
            Some(existing) if super::sections::SETTINGS.contains(&section.name.as_str()) => {
                super::sections::overlay(existing, section);
            }
            Some(existing) => existing.children.extend(section.children),
            None => tree.children.push(section),
        }
    }
    for attribute in child.tree.attributes {
        tree.set_attribute(&attribute.name, attribute.value);
    }
    let mut defaults = base.defaults;
    for (key, value) in child.defaults.iter() {
        defaults.set(key, value.clone());
    }
    let mut components = base.components;
    components.extend(child.components);
    Loaded {
        tree,
        tag: child.tag,
        components,
        defaults,
        verbatim: child.verbatim,
    }
}

fn set_origin(element: &mut Element, origin: usize) {
    element.origin = origin;
    for child in &mut element.children {
        set_origin(child, origin);
    }
}
