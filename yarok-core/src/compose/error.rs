//! Composition errors: where (component path, template, line:column, element, attribute,
//! expression) and what.

use std::fmt;

use crate::template::xml::{Attribute, Element, Position};

/// A problem found on an element, before the composer adds the component and template.
pub(super) type Problem = Box<(Element, Option<Attribute>, String)>;

/// A world could not be composed. Its [`ErrorDetails`] (reached through `Deref`) say where and
/// what.
#[derive(Clone, PartialEq, Eq)]
pub struct ComposeError(Box<ErrorDetails>);

crate::debug_as_report!(ComposeError);

impl From<ErrorDetails> for ComposeError {
    fn from(details: ErrorDetails) -> Self {
        Self(Box::new(details))
    }
}

impl std::ops::Deref for ComposeError {
    type Target = ErrorDetails;

    fn deref(&self) -> &ErrorDetails {
        &self.0
    }
}

/// Where a composition error is, and what it is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ErrorDetails {
    /// Path of the component being composed (`/`, `/arm`, `/arm/gripper`).
    pub component: String,
    /// The template file, or `<tag> (inline)` for an inline template.
    pub template: String,
    /// Where in the template, when known.
    pub position: Option<Position>,
    /// The element's tag, when known.
    pub element: Option<String>,
    /// The attribute, when the problem is in one.
    pub attribute: Option<String>,
    /// The expression, when the problem is in one.
    pub expression: Option<String>,
    /// What went wrong.
    pub message: String,
}

impl fmt::Display for ComposeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "component {}, {}", self.component, self.template)?;
        if let Some(position) = self.position {
            write!(f, ":{position}")?;
        }
        if let Some(element) = &self.element {
            write!(f, ", <{element}>")?;
        }
        if let Some(attribute) = &self.attribute {
            write!(f, " attribute `{attribute}`")?;
        }
        if let Some(expression) = &self.expression {
            write!(f, " expression `{expression}`")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for ComposeError {}
