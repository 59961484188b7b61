//! Recursion over element trees grows the stack on demand.
//!
//! Templates are bounded in depth (the composed world at most `MAX_WORLD_DEPTH` levels), but a
//! debug build spends kilobytes per level, and a user may compose on a thread with a small stack.
//! Each recursive walk over a tree calls [`deep`] before it descends, so no bounded input
//! overflows the stack of whatever thread composes it.

/// Room left on the stack below which the next level runs on a newly allocated segment.
const RED_ZONE: usize = 256 * 1024;
/// The size of each newly allocated segment.
const SEGMENT: usize = 2 * 1024 * 1024;

/// Runs `descend`, on a fresh stack segment if the current one is nearly used up.
pub(crate) fn deep<R>(descend: impl FnOnce() -> R) -> R {
    stacker::maybe_grow(RED_ZONE, SEGMENT, descend)
}
