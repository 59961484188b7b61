//! Where each line of the composed MJCF came from, so that errors MuJoCo reports against the
//! composed document (which the user never sees) can name the template the user wrote.

use std::fmt;

use super::Composition;
use crate::template::xml::{Element, Position};

/// Where an element of the composed MJCF was written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceLocation {
    /// Path of the component whose template holds the element (`/arm/gripper`).
    pub component: String,
    /// The template: its file, or `<tag> (inline template)`.
    pub template: String,
    /// Line and column of the element in the template.
    pub position: Position,
    /// The element's tag.
    pub element: String,
}

impl fmt::Display for SourceLocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "component {}, {}:{}:{}, <{}>",
            self.component, self.template, self.position.line, self.position.column, self.element
        )
    }
}

impl Composition {
    /// The element on `line` (counted from 1) of [`Composition::to_xml`]'s text, and where it
    /// was written; `None` past the end and for the elements the composer makes itself (the
    /// root and the sections that gather every component's content).
    pub fn source_of_line(&self, line: usize) -> Option<SourceLocation> {
        let mut current = 0;
        self.source_of(element_on_line(&self.mjcf, line, &mut current)?)
    }

    /// Where `element`, an element of [`Composition::mjcf`], was written; `None` for the
    /// elements the composer makes itself.
    pub fn source_of(&self, element: &Element) -> Option<SourceLocation> {
        if element.position.line == 0 {
            return None;
        }
        Some(SourceLocation {
            component: self.instances.get(element.owner)?.path.clone(),
            template: self.templates.get(element.origin)?.clone(),
            position: element.position,
            element: element.name.clone(),
        })
    }
}

/// Walks the lines [`Element::to_xml`] writes: one for an element without children, else an
/// opening line, its children's lines and a closing line.
fn element_on_line<'a>(
    element: &'a Element,
    line: usize,
    current: &mut usize,
) -> Option<&'a Element> {
    *current += 1;
    if *current == line {
        return Some(element);
    }
    if element.children.is_empty() || *current > line {
        return None;
    }
    for child in &element.children {
        if let Some(found) = crate::stack::deep(|| element_on_line(child, line, current)) {
            return Some(found);
        }
        if *current >= line {
            return None;
        }
    }
    *current += 1;
    (*current == line).then_some(element)
}
