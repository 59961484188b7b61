//! Merging the non-body sections of every component into the world.

use std::collections::HashMap;

use crate::template::xml::Element;

use super::error::Problem;

/// Sections holding global settings, merged attribute by attribute.
pub(super) const SETTINGS: [&str; 5] = ["compiler", "option", "size", "visual", "statistic"];

/// Why a component may not set the settings attribute `attribute` of `path` (`option`,
/// `option/flag`, `compiler`) unless the world sets it the same: MuJoCo applies it to the
/// whole world, the world's own bodies and every other component's included. Solver choices
/// (`integrator`, `cone`, `impratio`, …) a component may make, as a wrapped model needs them;
/// two components that disagree are refused as for any setting.
fn world_level(path: &str, attribute: &str) -> Option<&'static str> {
    match (path, attribute) {
        (
            "option",
            "timestep" | "gravity" | "wind" | "magnetic" | "density" | "viscosity" | "o_margin"
            | "o_solref" | "o_solimp" | "o_friction",
        ) => Some("the world's time step and physical constants"),
        ("option/flag", _) => Some("a flag that switches a part of the physics for every body"),
        ("compiler", "eulerseq") => Some("how every Euler angle of every body is read"),
        (
            "compiler",
            "settotalmass" | "boundmass" | "boundinertia" | "balanceinertia" | "inertiafromgeom"
            | "inertiagrouprange" | "alignfree" | "fusestatic",
        ) => Some("how the masses and inertias of every body are compiled"),
        ("compiler", "coordinate") => Some("how every position is read"),
        _ => None,
    }
}

/// The world's sections as components add to them.
#[derive(Default)]
pub(super) struct World {
    sections: Vec<Element>,
    /// Who set each settings attribute: (`option/flag`, `gravity`) → instance.
    setters: HashMap<(String, String), usize>,
}

impl World {
    pub(super) fn into_sections(self) -> Vec<Element> {
        self.sections
    }

    pub(super) fn merge(
        &mut self,
        section: Element,
        owner: usize,
        paths: &[String],
    ) -> Result<(), Problem> {
        if SETTINGS.contains(&section.name.as_str()) {
            let name = section.name.clone();
            let index = match self.sections.iter().position(|s| s.name == name) {
                Some(index) => index,
                None => {
                    self.sections.push(section.empty_like());
                    self.sections.len() - 1
                }
            };
            return self.merge_setting(index, Vec::new(), &name, section, owner, paths);
        }
        if section.name == "default" && owner != 0 {
            let index = self.section_index("default");
            self.sections[index].children.push(section);
            return Ok(());
        }
        match self.sections.iter_mut().find(|s| s.name == section.name) {
            Some(existing) => existing.children.extend(section.children),
            None => self.sections.push(section),
        }
        Ok(())
    }

    fn section_index(&mut self, name: &str) -> usize {
        match self.sections.iter().position(|s| s.name == name) {
            Some(index) => index,
            None => {
                self.sections.push(Element::new(name));
                self.sections.len() - 1
            }
        }
    }

    /// Merges `source` into the settings element at `index` then `trail` (child positions);
    /// `path` names that element (`visual/global`).
    fn merge_setting(
        &mut self,
        index: usize,
        trail: Vec<usize>,
        path: &str,
        source: Element,
        owner: usize,
        paths: &[String],
    ) -> Result<(), Problem> {
        for attribute in &source.attributes {
            let key = (path.to_owned(), attribute.name.clone());
            let target = walk_mut(&mut self.sections[index], &trail);
            let setter = self.setters.get(&key).copied().unwrap_or(0);
            match target.attribute(&attribute.name) {
                // One component setting a value twice (a file and what it includes): the later
                // one holds, as in MuJoCo.
                Some(_) if setter == owner => {
                    target.set_attribute(&attribute.name, &attribute.value)
                }
                Some(existing) if existing != attribute.value => {
                    let message = format!(
                        "{path}/@{} is {:?} here but {:?} in {}; components must agree on global settings",
                        attribute.name, attribute.value, existing, paths[setter]
                    );
                    return Err(Box::new((source.clone(), Some(attribute.clone()), message)));
                }
                Some(_) => {}
                None => {
                    if owner != 0
                        && let Some(what) = world_level(path, &attribute.name)
                    {
                        let message = format!(
                            "{path}/@{} would change the whole world, not this component: \
                             MuJoCo applies it to every body ({what}); set it in the world's \
                             template if the world is to have it",
                            attribute.name
                        );
                        return Err(Box::new((source.clone(), Some(attribute.clone()), message)));
                    }
                    target.attributes.push(attribute.clone());
                    self.setters.insert(key, owner);
                }
            }
        }
        for child in source.children {
            let target = walk_mut(&mut self.sections[index], &trail);
            let position = match target.children.iter().position(|c| c.name == child.name) {
                Some(position) => position,
                None => {
                    target.children.push(child.empty_like());
                    target.children.len() - 1
                }
            };
            let mut deeper = trail.clone();
            deeper.push(position);
            let child_path = format!("{path}/{}", child.name);
            self.merge_setting(index, deeper, &child_path, child, owner, paths)?;
        }
        Ok(())
    }
}

fn walk_mut<'a>(element: &'a mut Element, trail: &[usize]) -> &'a mut Element {
    trail.iter().fold(element, |at, &i| &mut at.children[i])
}

/// `extends`: the deriving template's settings override the base's.
pub(super) fn overlay(base: &mut Element, child: Element) {
    for attribute in child.attributes {
        base.set_attribute(&attribute.name, attribute.value);
    }
    for grandchild in child.children {
        match base.children.iter_mut().find(|c| c.name == grandchild.name) {
            Some(existing) => overlay(existing, grandchild),
            None => base.children.push(grandchild),
        }
    }
}

/// Several top-level `<default>` sections (say, one per included file) all describe MuJoCo's
/// main class; they become one: class defaults are kept in order, element defaults of the same
/// kind are overlaid, later attributes winning, as MuJoCo reads them.
pub(super) fn merge_top_level_defaults(sections: &mut Vec<Element>) {
    let Some(first) = sections.iter().position(|s| s.name == "default") else {
        return;
    };
    let mut later = Vec::new();
    let mut index = first + 1;
    while index < sections.len() {
        if sections[index].name == "default" {
            later.push(sections.remove(index));
        } else {
            index += 1;
        }
    }
    let main = &mut sections[first];
    for default in later {
        for attribute in default.attributes {
            main.set_attribute(&attribute.name, attribute.value);
        }
        for child in default.children {
            let same = main
                .children
                .iter_mut()
                .find(|c| c.name != "default" && c.name == child.name);
            match same {
                Some(existing) => {
                    for attribute in child.attributes {
                        existing.set_attribute(&attribute.name, attribute.value);
                    }
                }
                _ => main.children.push(child),
            }
        }
    }
}
