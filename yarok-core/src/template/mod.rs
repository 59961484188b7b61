//! MJCF component templates: the expression language, the XML tree, and expansion.

pub mod expr;
pub mod xml;
