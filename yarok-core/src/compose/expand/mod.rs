//! The composer: loads templates, expands them per instance and assembles the world.

use std::collections::{BTreeSet, HashMap, HashSet};
use std::path::PathBuf;

mod evaluate;

use evaluate::Scope;

use super::angles;
use super::error::{ErrorDetails, Problem};
use super::files;
use super::limits::{MAX_COMPONENT_DEPTH, MAX_ELEMENTS, MAX_WORLD_DEPTH};
use super::loader::{Loaded, Loader};
use super::mount::{collect_mounts, mount};
use super::namespace::{self as names, CLASSED};
use super::sections::World;
use super::{ComponentKeyframe, ComposeError, Composition, Instance, layout};
use crate::component::{ComponentType, NameKind, NameMap};
use crate::config::ConfigOrigins;
use crate::suggest::{did_you_mean, did_you_mean_or_list};
use crate::template::expr::{Expr, truthy};
use crate::template::xml::{Attribute, Element};
use crate::value::{Config, IntoValue, Overrides};

struct InstanceState {
    path: String,
    tag: String,
    component: ComponentType,
    config: Config,
    /// The component types usable in its template, by tag.
    components: Vec<(String, ComponentType)>,
    verbatim: bool,
}

/// What the expansion of one list of elements needs to know.
#[derive(Clone, Copy)]
struct Ctx<'p> {
    /// The instance whose template is being expanded (its components are usable as tags).
    owner: usize,
    /// The path new component tags are children of.
    base_path: &'p str,
    in_worldbody: bool,
    /// How deep in the composed world the elements being expanded are.
    depth: usize,
}

pub(super) struct Composer<'o> {
    overrides: &'o Overrides,
    /// Where each override was set (a file and key, a `--set`), when known.
    config_origins: Option<&'o ConfigOrigins>,
    used_overrides: HashSet<String>,
    loader: Loader,
    instances: Vec<InstanceState>,
    expressions: HashMap<String, Expr>,
    world: World,
    assets: BTreeSet<PathBuf>,
    keyframes: Vec<(usize, Element)>,
    /// Elements produced so far, bounded by [`MAX_ELEMENTS`].
    produced: usize,
    /// The instances whose templates are being expanded, outermost first.
    expanding: Vec<usize>,
    /// The world's `compiler/@angle`, to which every component's angles are converted.
    angle_unit: String,
}

impl<'o> Composer<'o> {
    pub(super) fn new(
        overrides: &'o Overrides,
        origins: Option<&'o ConfigOrigins>,
        runtime_world: Option<super::Declaration>,
    ) -> Self {
        Self {
            config_origins: origins,
            loader: Loader::new(runtime_world),
            produced: 0,
            overrides,
            used_overrides: HashSet::new(),
            instances: Vec::new(),
            expressions: HashMap::new(),
            world: World::default(),
            assets: BTreeSet::new(),
            keyframes: Vec::new(),
            expanding: Vec::new(),
            angle_unit: angles::DEFAULT_UNIT.to_owned(),
        }
    }

    pub(super) fn compose(mut self, world: ComponentType) -> Result<Composition, ComposeError> {
        let loaded = self.loader.load(world, "/")?;
        let config = self.configure(&loaded, "/", Vec::new(), None)?;
        let root_attributes = loaded.tree.attributes.clone();
        let body = self.instance(world, loaded, "/", config, 0)?;
        if let Some(unused) = self
            .overrides
            .keys()
            .find(|path| !self.used_overrides.contains(*path))
        {
            let paths: Vec<&str> = self.instances.iter().map(|i| i.path.as_str()).collect();
            let message = format!(
                "config names component {unused}, which the world does not have{}",
                did_you_mean_or_list(unused, paths)
            );
            let key = self.overrides[unused].keys().next().unwrap_or_default();
            return Err(self.override_error(unused, key, message));
        }
        let mut mjcf = Element::new("mujoco");
        mjcf.attributes = root_attributes;
        let mut worldbody = Element::new("worldbody");
        worldbody.children = body;
        mjcf.children = std::mem::take(&mut self.world).into_sections();
        mjcf.children.push(worldbody);
        let layout = layout::Layout::of(&mjcf, self.instances.len());
        let prefixes: Vec<String> = self
            .instances
            .iter()
            .map(|i| names::prefix(&i.path))
            .collect();
        let mut maps = vec![NameMap::default(); self.instances.len()];
        names::apply(&mut mjcf, &prefixes, &mut maps);
        let keyframes = self.lift_keyframes(&prefixes, &mut maps);
        let instances = self
            .instances
            .into_iter()
            .zip(maps)
            .enumerate()
            .map(|(id, (state, names))| Instance {
                path: state.path,
                tag: state.tag,
                component: state.component,
                config: state.config,
                names,
                joints: layout.joints[id].clone(),
                actuators: layout.actuators[id].clone(),
            })
            .collect();
        Ok(Composition {
            mjcf,
            instances,
            assets: self.assets.into_iter().collect(),
            keyframes,
            layout_known: layout.known,
            templates: self.loader.origins.into_iter().map(|o| o.label).collect(),
        })
    }

    fn lift_keyframes(
        &mut self,
        prefixes: &[String],
        maps: &mut [NameMap],
    ) -> Vec<ComponentKeyframe> {
        std::mem::take(&mut self.keyframes)
            .into_iter()
            .enumerate()
            .map(|(n, (owner, key))| {
                let local = key
                    .attribute("name")
                    .map_or_else(|| format!("key{n}"), str::to_owned);
                let name = format!("{}{local}", prefixes[owner]);
                maps[owner].insert(NameKind::Keyframe, &local, &name);
                let attributes = key
                    .attributes
                    .into_iter()
                    .filter(|a| a.name != "name")
                    .map(|a| (a.name, a.value))
                    .collect();
                ComponentKeyframe {
                    component: self.instances[owner].path.clone(),
                    name,
                    attributes,
                }
            })
            .collect()
    }

    /// Composes one component instance from its loaded template; returns its worldbody
    /// content. Its other sections go to the world.
    fn instance(
        &mut self,
        component: ComponentType,
        loaded: Loaded,
        path: &str,
        config: Config,
        depth: usize,
    ) -> Result<Vec<Element>, ComposeError> {
        self.expanding.push(self.instances.len());
        let body = self.expand_instance(component, loaded, path, config, depth);
        self.expanding.pop();
        body
    }

    fn expand_instance(
        &mut self,
        component: ComponentType,
        loaded: Loaded,
        path: &str,
        config: Config,
        depth: usize,
    ) -> Result<Vec<Element>, ComposeError> {
        let id = self.begin_instance(component, &loaded, path, &config);
        let mut tree = loaded.tree;
        set_owner(&mut tree, id);
        let scope = Scope {
            parent: None,
            vars: config
                .iter()
                .map(|(k, v)| (k.to_owned(), v.clone()))
                .collect(),
        };
        let ctx = Ctx {
            owner: id,
            base_path: path,
            in_worldbody: false,
            depth: 1,
        };
        let (worldbodies, sections): (Vec<Element>, Vec<Element>) = tree
            .children
            .into_iter()
            .partition(|section| section.name == "worldbody");
        let (conversion, has_defaults) = self.compose_sections(sections, &ctx, &scope)?;
        let body_ctx = Ctx {
            in_worldbody: true,
            depth,
            ..ctx
        };
        let mut body = Vec::new();
        for worldbody in worldbodies {
            body.extend(self.expand(worldbody.children, &body_ctx, &scope)?);
        }
        files::resolve(&mut body, &self.loader.origins, &mut self.assets)
            .map_err(|e| self.located(&e))?;
        if let Some(conversion) = &conversion {
            conversion.body(&mut body);
        }
        if id != 0 && has_defaults {
            set_missing_class(&mut body, true);
        }
        Ok(body)
    }

    /// Records a new instance of `component` at `path`; its id.
    fn begin_instance(
        &mut self,
        component: ComponentType,
        loaded: &Loaded,
        path: &str,
        config: &Config,
    ) -> usize {
        let components = loaded
            .components
            .iter()
            .map(|c| (self.tag_of(*c), *c))
            .collect();
        self.instances.push(InstanceState {
            path: path.to_owned(),
            tag: loaded.tag.clone(),
            component,
            config: config.clone(),
            components,
            verbatim: loaded.verbatim,
        });
        self.instances.len() - 1
    }

    /// Expands an instance's sections other than `<worldbody>` and merges them into the world;
    /// the angle conversion its body needs, and whether it has defaults.
    fn compose_sections(
        &mut self,
        sections: Vec<Element>,
        ctx: &Ctx<'_>,
        scope: &Scope<'_>,
    ) -> Result<(Option<angles::Conversion>, bool), ComposeError> {
        let id = ctx.owner;
        let mut sections = self.expand(sections, ctx, scope)?;
        files::resolve(&mut sections, &self.loader.origins, &mut self.assets)
            .map_err(|e| self.located(&e))?;
        super::sections::merge_top_level_defaults(&mut sections);
        let has_defaults = sections.iter().any(|s| s.name == "default");
        let conversion = self.angle_conversion(&mut sections, id)?;
        if let Some(conversion) = &conversion {
            conversion.defaults(&mut sections);
        }
        if id != 0 {
            for section in &mut sections {
                if section.name == "default" {
                    section.set_attribute("class", "main");
                } else if has_defaults {
                    set_missing_class(&mut section.children, false);
                }
            }
        }
        self.merge_sections(sections, id)?;
        Ok((conversion, has_defaults))
    }

    /// The world takes the first instance's angle unit; another instance's angles are converted
    /// to it, and its `<compiler angle>` dropped.
    fn angle_conversion(
        &mut self,
        sections: &mut [Element],
        id: usize,
    ) -> Result<Option<angles::Conversion>, ComposeError> {
        let unit = angles::unit_of(sections)
            .map_err(|(compiler, angle)| {
                self.error(
                    compiler,
                    Some(angle),
                    None,
                    format!(
                        "angle must be \"degree\" or \"radian\", as MuJoCo reads it, not {:?}",
                        angle.value
                    ),
                )
            })?
            .to_owned();
        if id == 0 {
            self.angle_unit = unit;
            return Ok(None);
        }
        for compiler in sections.iter_mut().filter(|s| s.name == "compiler") {
            compiler.take_attribute("angle");
        }
        Ok(angles::factor(&unit, &self.angle_unit)
            .map(|factor| angles::Conversion::new(sections, id, factor)))
    }

    /// Keyframes are kept for the end; every other section is merged into the world's.
    fn merge_sections(&mut self, sections: Vec<Element>, id: usize) -> Result<(), ComposeError> {
        for section in sections {
            if section.name == "keyframe" {
                self.keyframes
                    .extend(section.children.into_iter().map(|key| (id, key)));
                continue;
            }
            let paths: Vec<String> = self.instances.iter().map(|i| i.path.clone()).collect();
            self.world
                .merge(section, id, &paths)
                .map_err(|e| self.located(&e))?;
        }
        Ok(())
    }

    fn expand(
        &mut self,
        elements: Vec<Element>,
        ctx: &Ctx<'_>,
        scope: &Scope<'_>,
    ) -> Result<Vec<Element>, ComposeError> {
        if self.instances[ctx.owner].verbatim {
            return Ok(elements);
        }
        let mut out = Vec::with_capacity(elements.len());
        for mut element in elements {
            if let Some(condition) = element.take_attribute("if") {
                let value = self.eval(&condition.value, &element, Some(&condition), scope)?;
                if !truthy(&value.0) {
                    continue;
                }
            }
            match element.name.as_str() {
                "for" => out.extend(self.expand_for(&element, ctx, scope)?),
                "if" => {
                    let the = required(&element, "the")
                        .map_err(|m| self.error(&element, None, None, m))?;
                    if truthy(&self.eval(&the.value, &element, Some(&the), scope)?.0) {
                        out.extend(self.expand(element.children, ctx, scope)?);
                    }
                }
                tag if element.attribute("parent").is_some() => {
                    let parent = element.attribute_entry("parent").cloned();
                    let message = format!(
                        "`parent` places an element written directly inside a component tag \
                         (<arm><{tag} parent=\"wrist\"/></arm>) on that component's body or \
                         site; this <{tag}> is not"
                    );
                    return Err(self.error(&element, parent.as_ref(), None, message));
                }
                tag => match self.component_for(ctx.owner, tag) {
                    Some(component) if ctx.in_worldbody => {
                        out.extend(self.instantiate(component, element, ctx, scope)?)
                    }
                    Some(_) => {
                        return Err(self.error(
                            &element,
                            None,
                            None,
                            "component tags belong in <worldbody>".into(),
                        ));
                    }
                    None => out.push(self.expand_mjcf(element, ctx, scope)?),
                },
            }
        }
        Ok(out)
    }

    /// `<for each="…" as="name">`: its children once per item, `name` bound to the item.
    fn expand_for(
        &mut self,
        element: &Element,
        ctx: &Ctx<'_>,
        scope: &Scope<'_>,
    ) -> Result<Vec<Element>, ComposeError> {
        let each = required(element, "each").map_err(|m| self.error(element, None, None, m))?;
        let name = required(element, "as").map_err(|m| self.error(element, None, None, m))?;
        if !crate::template::expr::is_variable_name(&name.value) {
            return Err(self.error(
                element,
                Some(&name),
                Some(&name.value),
                format!(
                    "`as` names the loop's variable: {:?} is not a name (letters, \
                     digits and _, not starting with a digit, not a keyword)",
                    name.value
                ),
            ));
        }
        let value = self.eval(&each.value, element, Some(&each), scope)?;
        let items = match (value.to_list(), value.as_str()) {
            (Some(items), _) => items,
            (_, Some(s)) => s.chars().map(|c| c.to_string().into_value()).collect(),
            _ => {
                return Err(self.error(
                    element,
                    Some(&each),
                    Some(&each.value),
                    format!("cannot loop over {value}"),
                ));
            }
        };
        let mut out = Vec::new();
        for item in items {
            let inner = Scope {
                parent: Some(scope),
                vars: vec![(name.value.clone(), item)],
            };
            out.extend(self.expand(element.children.clone(), ctx, &inner)?);
        }
        Ok(out)
    }

    /// An MJCF element: its attributes interpolated, its children expanded, within the limits.
    fn expand_mjcf(
        &mut self,
        mut element: Element,
        ctx: &Ctx<'_>,
        scope: &Scope<'_>,
    ) -> Result<Element, ComposeError> {
        if !super::elements::is_mjcf_element(&element.name) {
            let message = self.unknown_tag(ctx.owner, &element.name);
            return Err(self.error(&element, None, None, message));
        }
        self.produced += 1;
        if self.produced > MAX_ELEMENTS {
            let message = format!("the world expands to more than {MAX_ELEMENTS} elements");
            return Err(self.error(&element, None, None, message));
        }
        if ctx.depth >= MAX_WORLD_DEPTH {
            let message =
                format!("the composed world nests elements deeper than {MAX_WORLD_DEPTH}");
            return Err(self.error(&element, None, None, message));
        }
        self.interpolate(&mut element, scope)?;
        let children = std::mem::take(&mut element.children);
        let inner = Ctx {
            depth: ctx.depth + 1,
            ..*ctx
        };
        element.children = crate::stack::deep(|| self.expand(children, &inner, scope))?;
        Ok(element)
    }

    /// Why `tag` cannot be used in `owner`'s template, with the nearest tag that can.
    fn unknown_tag(&self, owner: usize, tag: &str) -> String {
        let instance = &self.instances[owner];
        let usable = instance.components.iter().map(|(t, _)| t.as_str());
        let hint = did_you_mean(tag, usable.clone().chain(super::MJCF_ELEMENTS));
        let uses = if instance.components.is_empty() {
            format!("<{}> uses no components", instance.tag)
        } else {
            let tags: Vec<String> = usable.map(|t| format!("<{t}>")).collect();
            format!("<{}> uses {}", instance.tag, tags.join(", "))
        };
        format!("<{tag}> is neither an MJCF element nor a component tag ({uses}){hint}")
    }

    fn component_for(&self, owner: usize, tag: &str) -> Option<ComponentType> {
        self.instances[owner]
            .components
            .iter()
            .rev()
            .find(|(t, _)| t == tag)
            .map(|(_, c)| *c)
    }

    /// A component type's tag, from its loaded template when there is one.
    fn tag_of(&mut self, component: ComponentType) -> String {
        self.loader.tag_of(component)
    }

    fn instantiate(
        &mut self,
        component: ComponentType,
        mut tag: Element,
        ctx: &Ctx<'_>,
        scope: &Scope<'_>,
    ) -> Result<Vec<Element>, ComposeError> {
        let (name_attribute, path) = self.instance_path(&mut tag, ctx, scope)?;
        self.check_nesting(component, &tag, &name_attribute, &path)?;
        let loaded = self.loader.load(component, &path)?;
        let mut assigned = Vec::new();
        for attribute in std::mem::take(&mut tag.attributes) {
            let value = self.attribute_value(&attribute, &tag, scope)?;
            assigned.push((attribute, value));
        }
        let config = self.configure(&loaded, &path, assigned, Some(&tag))?;
        let sub_id = self.instances.len();
        let mut body = self.instance(component, loaded, &path, config, ctx.depth)?;
        let nested_ctx = Ctx {
            base_path: &path,
            ..*ctx
        };
        for mut child in std::mem::take(&mut tag.children) {
            let Some(parent) = child.take_attribute("parent") else {
                body.extend(self.expand(vec![child], &nested_ctx, scope)?);
                continue;
            };
            let carrier = child.without_children();
            let expanded = self.expand(vec![child], &nested_ctx, scope)?;
            if mount(&mut body, sub_id, &parent.value, expanded).is_err() {
                let mut mounts = Vec::new();
                collect_mounts(&body, sub_id, &mut mounts);
                let hint = did_you_mean_or_list(&parent.value, mounts.iter().map(String::as_str));
                let message = format!("{path} has no body or site named {:?}{hint}", parent.value);
                return Err(self.error(&carrier, Some(&parent), None, message));
            }
        }
        Ok(body)
    }

    /// The path of the component `tag` names: its `name` (taken from it), checked, under the
    /// context's path, and not taken yet.
    fn instance_path(
        &mut self,
        tag: &mut Element,
        ctx: &Ctx<'_>,
        scope: &Scope<'_>,
    ) -> Result<(Attribute, String), ComposeError> {
        let name_attribute = tag
            .take_attribute("name")
            .ok_or_else(|| self.error(tag, None, None, "a component tag needs a `name`".into()))?;
        let name = self
            .attribute_value(&name_attribute, tag, scope)?
            .to_string();
        if name.is_empty() || name.contains('/') || name.contains(char::is_whitespace) {
            return Err(self.error(
                tag,
                Some(&name_attribute),
                None,
                format!("{name:?} is not a valid component name"),
            ));
        }
        let path = if ctx.base_path == "/" {
            format!("/{name}")
        } else {
            format!("{}/{name}", ctx.base_path)
        };
        if self.instances.iter().any(|i| i.path == path) {
            return Err(self.error(
                tag,
                Some(&name_attribute),
                None,
                format!("a component named {path} already exists"),
            ));
        }
        Ok((name_attribute, path))
    }

    /// Refuses a component inside itself (directly or through others) and nesting too deep.
    fn check_nesting(
        &self,
        component: ComponentType,
        tag: &Element,
        name: &Attribute,
        path: &str,
    ) -> Result<(), ComposeError> {
        let outer = self
            .expanding
            .iter()
            .map(|&id| &self.instances[id])
            .find(|instance| instance.component.type_id() == component.type_id());
        if let Some(outer) = outer {
            let message = format!(
                "component <{}> uses itself: {path} is inside {}, another <{}>",
                tag.name,
                if outer.path == "/" {
                    "the world"
                } else {
                    &outer.path
                },
                outer.tag
            );
            return Err(self.error(tag, Some(name), None, message));
        }
        if self.expanding.len() >= MAX_COMPONENT_DEPTH {
            let message = format!("{path} nests components deeper than {MAX_COMPONENT_DEPTH}");
            return Err(self.error(tag, Some(name), None, message));
        }
        Ok(())
    }

    fn error(
        &self,
        element: &Element,
        attribute: Option<&Attribute>,
        expression: Option<&str>,
        message: String,
    ) -> ComposeError {
        ComposeError::from(ErrorDetails {
            component: self
                .instances
                .get(element.owner)
                .map_or_else(|| "/".to_owned(), |i| i.path.clone()),
            template: self
                .loader
                .origins
                .get(element.origin)
                .map_or_else(String::new, |o| o.label.clone()),
            position: Some(attribute.map_or(element.position, |a| a.position)),
            element: Some(element.name.clone()),
            attribute: attribute.map(|a| a.name.clone()),
            expression: expression.map(str::to_owned),
            message,
        })
    }

    /// An error in the config value `key` for the component at `path`, placed where the value
    /// was set (a file and key, a `--set`).
    fn override_error(&self, path: &str, key: &str, message: String) -> ComposeError {
        let origin = self.config_origins.map_or_else(
            || "run configuration".to_owned(),
            |o| o.describe("components", path, key),
        );
        ComposeError::from(ErrorDetails {
            component: path.to_owned(),
            template: origin,
            position: None,
            element: None,
            attribute: Some(key.to_owned()),
            expression: None,
            message,
        })
    }

    fn located(&self, problem: &Problem) -> ComposeError {
        let (element, attribute, message) = &**problem;
        self.error(element, attribute.as_ref(), None, message.clone())
    }
}

fn set_owner(element: &mut Element, owner: usize) {
    element.owner = owner;
    for child in &mut element.children {
        set_owner(child, owner);
    }
}

/// Gives a component's top-level elements its own default class, so that its `<default>`
/// applies to it and not to the world.
fn set_missing_class(elements: &mut [Element], in_worldbody: bool) {
    for element in elements {
        let attribute = if in_worldbody && matches!(element.name.as_str(), "body" | "frame") {
            "childclass"
        } else {
            "class"
        };
        let takes_class = attribute == "childclass" || CLASSED.contains(&element.name.as_str());
        if takes_class && element.attribute(attribute).is_none() {
            element.set_attribute(attribute, "main");
        }
    }
}

fn required(element: &Element, name: &str) -> Result<Attribute, String> {
    element
        .attribute_entry(name)
        .cloned()
        .ok_or_else(|| format!("<{}> needs a `{name}` attribute", element.name))
}
