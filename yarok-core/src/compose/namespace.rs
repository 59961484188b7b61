//! Namespacing: every name a component defines and every reference to one gets the component's
//! path as prefix, so that the same component can be used twice in a world.

use crate::component::{NameKind, NameMap};
use crate::template::xml::Element;

/// Attributes that define or reference a name in MJCF. The same attribute name means the same
/// thing on every element that has it (`site` always names a site, `target` a body, …).
const NAME_ATTRIBUTES: [&str; 36] = [
    "name",
    "class",
    "childclass",
    "material",
    "mesh",
    "hfield",
    "texture",
    "target",
    "site",
    "joint",
    "tendon",
    "actuator",
    "body",
    "geom",
    "body1",
    "body2",
    "geom1",
    "geom2",
    "site1",
    "site2",
    "joint1",
    "joint2",
    "tendon1",
    "tendon2",
    "jointinparent",
    "refsite",
    "cranksite",
    "slidersite",
    "objname",
    "refname",
    "sidesite",
    "camera",
    "subtree1",
    "subtree2",
    "flex",
    "prefix",
];

/// The prefix of a component path: `""` for the world `/`, `"arm/gripper/"` for `/arm/gripper`.
pub(crate) fn prefix(path: &str) -> String {
    let trimmed = path.trim_matches('/');
    if trimmed.is_empty() {
        String::new()
    } else {
        format!("{trimmed}/")
    }
}

/// A reference written in a component: local names get the prefix; a leading `/` makes it
/// absolute (`"/floor"` is the world's `floor`).
fn qualify(prefix: &str, value: &str) -> String {
    match value.strip_prefix('/') {
        Some(absolute) => absolute.to_owned(),
        None if value.is_empty() => String::new(),
        None => format!("{prefix}{value}"),
    }
}

/// Renames every element by its owner's prefix and fills each owner's [`NameMap`].
pub(crate) fn apply(root: &mut Element, prefixes: &[String], maps: &mut [NameMap]) {
    for section in &mut root.children {
        let section_tag = section.name.clone();
        rename(section, &section_tag, prefixes, maps);
    }
}

fn rename(element: &mut Element, section: &str, prefixes: &[String], maps: &mut [NameMap]) {
    let prefix = &prefixes[element.owner];
    let defines = if element.name == "default" {
        "class"
    } else {
        "name"
    };
    for attribute in &mut element.attributes {
        if !NAME_ATTRIBUTES.contains(&attribute.name.as_str()) {
            continue;
        }
        let qualified = qualify(prefix, &attribute.value);
        if attribute.name == defines && !attribute.value.starts_with('/') {
            let kind = NameKind::of(&element.name, section);
            maps[element.owner].insert(kind, &attribute.value, &qualified);
        }
        attribute.value = qualified;
    }
    if !element.children.is_empty() {
        crate::stack::deep(|| {
            for child in &mut element.children {
                rename(child, section, prefixes, maps);
            }
        });
    }
}

/// Elements that take a `class` attribute (MuJoCo 4.0's XML reference).
pub(crate) const CLASSED: [&str; 29] = [
    "adhesion",
    "cylinder",
    "damper",
    "dcmotor",
    "general",
    "intvelocity",
    "motor",
    "muscle",
    "orientation",
    "pid",
    "plugin",
    "position",
    "velocity",
    "material",
    "mesh",
    "texture",
    "camera",
    "geom",
    "joint",
    "light",
    "site",
    "pair",
    "connect",
    "flex",
    "flexstrain",
    "tendon",
    "weld",
    "fixed",
    "spatial",
];
