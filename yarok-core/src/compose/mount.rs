//! Placing the elements written inside a component tag with `parent=`: in one of the
//! component's bodies, or at one of its sites.

use crate::template::xml::Element;

/// The attributes that give a site its place in its body, which a `<frame>` takes as well.
const FRAME_ATTRIBUTES: [&str; 6] = ["pos", "quat", "axisangle", "xyaxes", "zaxis", "euler"];

/// Places `children` in `owner`'s body named `name`, or at its site named `name` (inside a
/// `<frame>` with the site's position and orientation, next to the site, as MuJoCo's attach
/// does). Gives `children` back when `owner` has neither.
pub(super) fn mount(
    elements: &mut Vec<Element>,
    owner: usize,
    name: &str,
    children: Vec<Element>,
) -> Result<(), Vec<Element>> {
    let is_named = |e: &Element, tag: &str| {
        e.name == tag && e.owner == owner && e.attribute("name") == Some(name)
    };
    if let Some(site) = elements.iter().find(|e| is_named(e, "site")) {
        let mut frame = site.without_children();
        frame.name = "frame".to_owned();
        frame
            .attributes
            .retain(|a| FRAME_ATTRIBUTES.contains(&a.name.as_str()));
        frame.children = children;
        elements.push(frame);
        return Ok(());
    }
    let mut children = children;
    for element in elements.iter_mut() {
        if is_named(element, "body") {
            element.children.extend(children);
            return Ok(());
        }
        children = match crate::stack::deep(|| mount(&mut element.children, owner, name, children))
        {
            Ok(()) => return Ok(()),
            Err(children) => children,
        };
    }
    Err(children)
}

/// The names of `owner`'s bodies and sites.
pub(super) fn collect_mounts(elements: &[Element], owner: usize, out: &mut Vec<String>) {
    for element in elements {
        if matches!(element.name.as_str(), "body" | "site") && element.owner == owner {
            out.extend(element.attribute("name").map(str::to_owned));
        }
        crate::stack::deep(|| collect_mounts(&element.children, owner, out));
    }
}
