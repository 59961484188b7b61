//! Tactile sensors in the world: components whose images come from the [`crate::tactile`]
//! optical models over the depth their internal cameras render.

mod digit;

pub use digit::{Contact, Digit};
