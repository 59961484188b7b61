//! Merging the non-body sections of every component into the world.

use std::collections::HashMap;

use crate::template::xml::{Attribute, Element};

use super::error::Problem;

/// Sections holding global settings, merged attribute by attribute.
pub(super) const SETTINGS: [&str; 5] = ["compiler", "option", "size", "visual", "statistic"];

/// The world's sections as components add to them.
#[derive(Default)]
pub(super) struct World {
    sections: Vec<Element>,
    /// Who set each settings attribute: (`option/flag`, `gravity`) → instance.
    setters: HashMap<(String, String), usize>,
    /// Components that write angles: who, in which unit, and the first angle they write.
    angle_writers: Vec<(usize, String, Element, Attribute)>,
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
            let index = self.section_index(&name);
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
            match target.attribute(&attribute.name) {
                Some(existing) if existing != attribute.value => {
                    let setter = self.setters.get(&key).copied().unwrap_or(0);
                    let message = format!(
                        "{path}/@{} is {:?} here but {:?} in {}; components must agree on global settings",
                        attribute.name, attribute.value, existing, paths[setter]
                    );
                    return Err(Box::new((source.clone(), Some(attribute.clone()), message)));
                }
                Some(_) => {}
                None => {
                    target.attributes.push(attribute.clone());
                    self.setters.insert(key, owner);
                }
            }
        }
        for child in source.children {
            let target = walk_mut(&mut self.sections[index], &trail);
            match target.children.iter().position(|c| c.name == child.name) {
                Some(position) => {
                    let mut deeper = trail.clone();
                    deeper.push(position);
                    let child_path = format!("{path}/{}", child.name);
                    self.merge_setting(index, deeper, &child_path, child, owner, paths)?;
                }
                None => target.children.push(child),
            }
        }
        Ok(())
    }

    /// Records the unit a component writes its angles in (its own `compiler/@angle`, MuJoCo's
    /// default degree), if it writes any.
    pub(super) fn note_angles(&mut self, body: &[Element], sections: &[Element], owner: usize) {
        let unit = sections
            .iter()
            .find(|s| s.name == "compiler")
            .and_then(|c| c.attribute("angle"))
            .unwrap_or("degree");
        if let Some((element, attribute)) = first_angle(body).or_else(|| first_angle(sections)) {
            self.angle_writers
                .push((owner, unit.to_owned(), element.clone(), attribute.clone()));
        }
    }

    /// Every component that writes angles must use the world's unit: one `compiler/@angle`
    /// applies to the whole model.
    pub(super) fn check_angles(&self, paths: &[String]) -> Result<(), Problem> {
        let world = self
            .sections
            .iter()
            .find(|s| s.name == "compiler")
            .and_then(|c| c.attribute("angle"));
        let unit = world.unwrap_or("degree");
        let decided_by = self
            .setters
            .get(&("compiler".to_owned(), "angle".to_owned()))
            .map_or("MuJoCo's default", |&o| paths[o].as_str());
        match self.angle_writers.iter().find(|(_, own, _, _)| own != unit) {
            Some((owner, own, element, attribute)) => Err(Box::new((
                element.clone(),
                Some(attribute.clone()),
                format!(
                    "{} writes angles in {own}, but the world's compiler/@angle is {unit} (set by {decided_by}); \
                     set the same angle unit in both",
                    paths[*owner]
                ),
            ))),
            None => Ok(()),
        }
    }
}
/// The first attribute whose value is an angle (`euler`, `axisangle`, a hinge's `range`).
fn first_angle(elements: &[Element]) -> Option<(&Element, &Attribute)> {
    for element in elements {
        let angular_joint =
            element.name == "joint" && !matches!(element.attribute("type"), Some("slide" | "free"));
        for attribute in &element.attributes {
            let angle = matches!(attribute.name.as_str(), "euler" | "axisangle")
                || (angular_joint
                    && matches!(attribute.name.as_str(), "range" | "ref" | "springref"));
            if angle {
                return Some((element, attribute));
            }
        }
        if let Some(found) = first_angle(&element.children) {
            return Some(found);
        }
    }
    None
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
