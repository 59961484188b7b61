//! Row-by-row image passes: three rows of an intermediate result kept while a pass walks down
//! the image, so that each row is computed once and every buffer stays in cache.

use super::filter::reflect_101;

/// Three rows of a per-row result, each stored with its row index (slot `row % 3`, so that any
/// three consecutive rows coexist).
#[derive(Debug, Clone)]
pub(crate) struct RowRing<T> {
    slots: [(usize, T); 3],
}

impl<T: Default> Default for RowRing<T> {
    fn default() -> Self {
        Self {
            slots: Default::default(),
        }
    }
}

impl<T> RowRing<T> {
    /// Forgets every row (a new frame), letting `prepare` size each slot's buffers.
    pub(crate) fn reset(&mut self, mut prepare: impl FnMut(&mut T)) {
        for (index, slot) in &mut self.slots {
            *index = usize::MAX;
            prepare(slot);
        }
    }

    /// The slot of `row` if the ring does not hold it yet, to be filled by the caller (a slot
    /// rather than a closure, so that the computation inlines into SIMD-multiversioned callers).
    #[inline(always)]
    pub(crate) fn claim(&mut self, row: usize) -> Option<&mut T> {
        let (index, slot) = &mut self.slots[row % 3];
        if *index == row {
            return None;
        }
        *index = row;
        Some(slot)
    }

    /// Row `row`, which [`RowRing::claim`] has handed out.
    #[inline(always)]
    pub(crate) fn get(&self, row: usize) -> &T {
        let (index, slot) = &self.slots[row % 3];
        debug_assert_eq!(*index, row, "row {row} is not in the ring");
        slot
    }
}

/// The rows above and below `row` in an image `height` rows high, with OpenCV's default border
/// (reflect-101: above the first row is the second).
#[inline(always)]
pub(crate) fn neighbours(row: usize, height: usize) -> [usize; 3] {
    let height = height as i64;
    [
        reflect_101(row as i64 - 1, height),
        row,
        reflect_101(row as i64 + 1, height),
    ]
}
