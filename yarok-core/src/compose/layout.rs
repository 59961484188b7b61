//! Where each component's joints and actuators land in the compiled model's arrays, in MuJoCo's
//! order: bodies depth first in document order (frames are transparent), each body's joints in
//! document order; actuators in the order of the `<actuator>` section.

use crate::template::xml::Element;

/// Elements that create bodies or joints the composer cannot count.
const GENERATORS: [&str; 5] = ["composite", "flexcomp", "replicate", "attach", "include"];

pub(super) struct Layout {
    pub(super) joints: Vec<Vec<usize>>,
    pub(super) actuators: Vec<Vec<usize>>,
    pub(super) known: bool,
}

impl Layout {
    pub(super) fn of(mjcf: &Element, instances: usize) -> Self {
        let mut layout = Self {
            joints: vec![Vec::new(); instances],
            actuators: vec![Vec::new(); instances],
            known: true,
        };
        let mut joint_count = 0;
        for worldbody in mjcf.children.iter().filter(|s| s.name == "worldbody") {
            let mut bodies = Vec::new();
            child_bodies(worldbody, &mut bodies, &mut layout.known);
            for body in bodies {
                layout.body(body, &mut joint_count);
            }
        }
        let actuators = mjcf
            .children
            .iter()
            .filter(|s| s.name == "actuator")
            .flat_map(|s| &s.children);
        for (index, actuator) in actuators.enumerate() {
            layout.actuators[actuator.owner].push(index);
        }
        layout
    }

    fn body(&mut self, body: &Element, count: &mut usize) {
        let mut joints = Vec::new();
        body_joints(body, &mut joints);
        for joint in joints {
            self.joints[joint.owner].push(*count);
            *count += 1;
        }
        let mut children = Vec::new();
        child_bodies(body, &mut children, &mut self.known);
        for child in children {
            self.body(child, count);
        }
    }
}

/// A body's own joints, looking through frames.
fn body_joints<'a>(element: &'a Element, out: &mut Vec<&'a Element>) {
    for child in &element.children {
        match child.name.as_str() {
            "joint" | "freejoint" => out.push(child),
            "frame" => body_joints(child, out),
            _ => {}
        }
    }
}

/// The bodies directly below `element`, looking through frames.
fn child_bodies<'a>(element: &'a Element, out: &mut Vec<&'a Element>, known: &mut bool) {
    for child in &element.children {
        match child.name.as_str() {
            "body" => out.push(child),
            "frame" => child_bodies(child, out, known),
            name if GENERATORS.contains(&name) => *known = false,
            _ => {}
        }
    }
}
