//! Row-by-row image passes: three rows of an intermediate result kept while a pass walks down
//! the image, so that each row is computed once and every buffer stays in cache.

use std::ops::Range;

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

/// Bands per thread of a parallel [`in_bands_with`]: a thread that finishes its band early (the
/// other was slowed down by the rest of the machine) takes another. Measured on the DIGIT model
/// on 2 cores, 4 beat 1 by about 5 % a frame in three paired runs.
#[cfg(feature = "parallel")]
const BANDS_PER_THREAD: usize = 4;

/// Runs `work` over `rows` of an image whose rows, `row_len` elements each, are exactly `out`:
/// in one call, or, when `parallel` (and the `parallel` feature is on), in `BANDS_PER_THREAD`
/// bands of rows per thread of rayon's pool, each band with its own scratch from `scratch`
/// (grown as needed). Every row is computed from the same inputs whichever band it falls in, so
/// the output does not depend on the split.
pub(crate) fn in_bands_with<T: Send, S: Default + Send>(
    rows: Range<usize>,
    row_len: usize,
    out: &mut [T],
    scratch: &mut Vec<S>,
    parallel: bool,
    work: impl Fn(Range<usize>, &mut S, &mut [T]) + Sync,
) {
    if scratch.is_empty() {
        scratch.push(S::default());
    }
    #[cfg(feature = "parallel")]
    if parallel && rows.len() > 1 && row_len > 0 {
        let bands = (BANDS_PER_THREAD * rayon::current_num_threads()).min(rows.len());
        let band_rows = rows.len().div_ceil(bands);
        if scratch.len() < bands {
            scratch.resize_with(bands, S::default);
        }
        let start = rows.start;
        let band_range = |band: usize| {
            let first = start + band * band_rows;
            first..(first + band_rows).min(rows.end)
        };
        let mut bands = out.chunks_mut(band_rows * row_len).zip(scratch.iter_mut());
        let (first_out, first_scratch) = bands.next().expect("at least one band");
        let work = &work;
        // The calling thread takes the first band itself.
        rayon::in_place_scope(|scope| {
            for (band, (out, scratch)) in bands.enumerate() {
                scope.spawn(move |_| work(band_range(band + 1), scratch, out));
            }
            work(band_range(0), first_scratch, first_out);
        });
        return;
    }
    #[cfg(not(feature = "parallel"))]
    let _ = (parallel, row_len);
    work(rows, &mut scratch[0], out);
}

/// [`in_bands_with`] for work that needs no scratch.
pub(crate) fn in_bands<T: Send>(
    rows: Range<usize>,
    row_len: usize,
    out: &mut [T],
    parallel: bool,
    work: impl Fn(Range<usize>, &mut [T]) + Sync,
) {
    // A vector of `()` never allocates.
    let mut none: Vec<()> = Vec::new();
    in_bands_with(rows, row_len, out, &mut none, parallel, |rows, (), out| {
        work(rows, out)
    });
}

/// Runs `a` and `b`, on two threads of rayon's pool when `parallel` (and the `parallel` feature
/// is on), one after the other otherwise.
pub(crate) fn join<A: Send, B: Send>(
    parallel: bool,
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    #[cfg(feature = "parallel")]
    if parallel {
        return rayon::join(a, b);
    }
    #[cfg(not(feature = "parallel"))]
    let _ = parallel;
    (a(), b())
}
