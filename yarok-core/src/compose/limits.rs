//! How big a composed world may get, so that no template exhausts memory or the stack.

/// Loops may not expand a world beyond this many elements, so that no template exhausts memory.
pub(super) const MAX_ELEMENTS: usize = 1_000_000;
/// Components may not nest deeper than this (a world is rarely deeper than 5).
pub(super) const MAX_COMPONENT_DEPTH: usize = 32;
/// Elements of the composed world may not nest deeper than this, so that no chain of templates
/// can exhaust the stack of the composer, the MJCF writer or MuJoCo's parser.
pub(super) const MAX_WORLD_DEPTH: usize = 512;
