//! A component's angles in the world's unit.
//!
//! One `compiler/@angle` applies to a whole MuJoCo model, so a component written in another
//! unit than the world (a third-party file in degrees in a world in radians) has its angles
//! converted when it is composed: every attribute MuJoCo reads as an angle, namely `euler` (all
//! three), the angle of `axisangle`, and `range`, `ref` and `springref` of hinge and ball joints,
//! in the body and in default classes (a joint's type may come from its class).

use std::collections::HashMap;

use crate::template::xml::{Attribute, Element};

/// The units `compiler/@angle` may name.
const UNITS: [&str; 2] = ["degree", "radian"];

/// MuJoCo's unit when `compiler/@angle` is not given.
pub(super) const DEFAULT_UNIT: &str = "degree";

/// The unit the `compiler` among `sections` sets, or MuJoCo's default; the `compiler` and its
/// attribute when one names a unit MuJoCo does not know.
pub(super) fn unit_of(sections: &[Element]) -> Result<&str, (&Element, &Attribute)> {
    let mut unit = None;
    for compiler in sections.iter().filter(|s| s.name == "compiler") {
        if let Some(angle) = compiler.attribute_entry("angle") {
            if !UNITS.contains(&angle.value.as_str()) {
                return Err((compiler, angle));
            }
            unit.get_or_insert(angle.value.as_str());
        }
    }
    Ok(unit.unwrap_or(DEFAULT_UNIT))
}

/// How to turn a number in `from` into `to` (`None` when the units are the same).
pub(super) fn factor(from: &str, to: &str) -> Option<f64> {
    match (from, to) {
        ("degree", "radian") => Some(std::f64::consts::PI / 180.0),
        ("radian", "degree") => Some(180.0 / std::f64::consts::PI),
        _ => None,
    }
}

/// Converts the angles one component wrote, by a factor.
pub(super) struct Conversion {
    types: JointTypes,
    owner: usize,
    factor: f64,
}

impl Conversion {
    /// The conversion of `owner`'s angles, whose default classes are in `sections`.
    pub(super) fn new(sections: &[Element], owner: usize, factor: f64) -> Self {
        let mut types = HashMap::new();
        for default in sections.iter().filter(|s| s.name == "default") {
            joint_types(default, "main", "hinge", &mut types);
        }
        Self {
            types: JointTypes(types),
            owner,
            factor,
        }
    }

    /// Converts the angles in the component's default classes.
    pub(super) fn defaults(&self, sections: &mut [Element]) {
        for default in sections.iter_mut().filter(|s| s.name == "default") {
            self.convert_defaults(default, "main");
        }
    }

    /// Converts the angles the component wrote in its worldbody content.
    pub(super) fn body(&self, elements: &mut [Element]) {
        self.convert_body(elements, "main");
    }

    fn convert_defaults(&self, default: &mut Element, class: &str) {
        let class = default.attribute("class").unwrap_or(class).to_owned();
        for child in &mut default.children {
            if child.name == "default" {
                crate::stack::deep(|| self.convert_defaults(child, &class));
            } else if child.owner == self.owner {
                let angular = child.name == "joint" && is_angular(self.types.of(&class));
                convert_element(child, angular, self.factor);
            }
        }
    }

    fn convert_body(&self, elements: &mut [Element], childclass: &str) {
        for element in elements {
            if element.owner == self.owner {
                let angular = element.name == "joint" && {
                    let class = element.attribute("class").unwrap_or(childclass);
                    is_angular(element.attribute("type").unwrap_or(self.types.of(class)))
                };
                convert_element(element, angular, self.factor);
            }
            let inner = element
                .attribute("childclass")
                .unwrap_or(childclass)
                .to_owned();
            crate::stack::deep(|| self.convert_body(&mut element.children, &inner));
        }
    }
}

/// The joint type each default class gives (inherited from its parent class).
struct JointTypes(HashMap<String, String>);

impl JointTypes {
    fn of(&self, class: &str) -> &str {
        self.0.get(class).map_or("hinge", String::as_str)
    }
}

fn joint_types(default: &Element, class: &str, inherited: &str, out: &mut HashMap<String, String>) {
    let class = default.attribute("class").unwrap_or(class);
    let own = default
        .children
        .iter()
        .find(|c| c.name == "joint")
        .and_then(|j| j.attribute("type"))
        .unwrap_or(inherited)
        .to_owned();
    for child in default.children.iter().filter(|c| c.name == "default") {
        crate::stack::deep(|| joint_types(child, class, &own, out));
    }
    out.insert(class.to_owned(), own);
}

fn is_angular(joint_type: &str) -> bool {
    matches!(joint_type, "hinge" | "ball")
}

fn convert_element(element: &mut Element, angular_joint: bool, factor: f64) {
    for attribute in &mut element.attributes {
        let scaled: &[usize] = match attribute.name.as_str() {
            "euler" => &[0, 1, 2],
            "axisangle" => &[3],
            "range" | "ref" | "springref" if angular_joint => &[0, 1],
            _ => continue,
        };
        if let Some(value) = scale(&attribute.value, scaled, factor) {
            attribute.value = value;
        }
    }
}

/// `value` with the numbers at `indices` multiplied by `factor`; `None` when it is not a list of
/// numbers (MuJoCo will report it).
fn scale(value: &str, indices: &[usize], factor: f64) -> Option<String> {
    let numbers: Vec<f64> = value
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .ok()?;
    let scaled: Vec<String> = numbers
        .iter()
        .enumerate()
        .map(|(i, x)| {
            let x = if indices.contains(&i) { x * factor } else { *x };
            format!("{x}")
        })
        .collect();
    Some(scaled.join(" "))
}
