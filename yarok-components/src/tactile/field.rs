//! Sparse Gaussian filtering for the elastic deformations: an image that equals a constant
//! outside a rectangle is blurred by computing only the rectangle (grown by the kernel's reach),
//! which is exact because a kernel summing to 1 maps a constant to itself. A press touches a small
//! part of the sensor, so most of the image is skipped.

use multiversion::multiversion;

use std::ops::Range;

use super::filter::{pad_reflect_101, reflect_101};
use super::rows::{in_bands, in_bands_with};

/// A rectangle of pixels: columns `x0..x1`, rows `y0..y1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Region {
    x0: usize,
    x1: usize,
    y0: usize,
    y1: usize,
}

impl Region {
    const EMPTY: Region = Region {
        x0: 0,
        x1: 0,
        y0: 0,
        y1: 0,
    };

    fn union(self, other: Region) -> Region {
        if other.is_empty() {
            return self;
        }
        if self.is_empty() {
            return other;
        }
        Region {
            x0: self.x0.min(other.x0),
            x1: self.x1.max(other.x1),
            y0: self.y0.min(other.y0),
            y1: self.y1.max(other.y1),
        }
    }

    fn is_empty(self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    /// Grown by a kernel's reach on each side; an axis that reaches a border spans the whole
    /// axis, since reflection there can carry values anywhere within reach.
    fn grown(self, before: usize, after: usize, width: usize, height: usize) -> Region {
        if self.is_empty() {
            return self;
        }
        let axis = |lo: usize, hi: usize, len: usize| {
            let (lo, hi) = (
                lo.saturating_sub(before.max(after)),
                (hi + before.max(after)).min(len),
            );
            if lo == 0 || hi == len {
                (0, len)
            } else {
                (lo, hi)
            }
        };
        let (x0, x1) = axis(self.x0, self.x1, width);
        let (y0, y1) = axis(self.y0, self.y1, height);
        Region { x0, x1, y0, y1 }
    }
}

/// A single-channel f32 image equal to `background` outside `region`.
#[derive(Debug, Clone)]
pub(crate) struct Field {
    pub(crate) values: Vec<f32>,
    width: usize,
    background: f32,
    region: Region,
}

impl Field {
    /// An empty field, to be filled with [`Field::assign`].
    pub(crate) fn empty() -> Self {
        Self {
            values: Vec::new(),
            width: 1,
            background: 0.0,
            region: Region::EMPTY,
        }
    }

    /// Fills the field with `values`, `width` wide; its background is taken as its minimum.
    pub(crate) fn assign(&mut self, width: usize, values: impl Iterator<Item = f32>) {
        self.values.clear();
        self.values.extend(values);
        self.width = width;
        self.background = min_of(&self.values);
        self.region = region_of(&self.values, width, self.background);
    }

    /// Makes this field a copy of `other`, reusing its memory.
    pub(crate) fn copy_from(&mut self, other: &Field) {
        self.values.clone_from(&other.values);
        self.width = other.width;
        self.background = other.background;
        self.region = other.region;
    }

    fn height(&self) -> usize {
        self.values.len() / self.width
    }

    /// The largest value.
    pub(crate) fn max(&self) -> f32 {
        let Region { x0, x1, y0, y1 } = self.region;
        (y0..y1)
            .map(|y| max_of(&self.values[y * self.width + x0..y * self.width + x1]))
            .fold(self.background, f32::max)
    }

    /// Writes the correlation with `kernel ⊗ kernel` (anchored at `len / 2`, reflect-101
    /// borders) into `out`, in bands of rows across threads when `parallel`.
    pub(crate) fn blur_into(
        &self,
        kernel: &[f32],
        scratch: &mut BlurScratch,
        out: &mut Field,
        parallel: bool,
    ) {
        let (width, height) = (self.width, self.height());
        let anchor = kernel.len() / 2;
        let region = self
            .region
            .grown(anchor, kernel.len() - 1 - anchor, width, height);
        let background = kernel.iter().map(|k| k * self.background).sum::<f32>();
        let BlurScratch { rows, padded } = scratch;
        rows.clear();
        rows.resize(self.values.len(), self.background);
        let columns = (region.x0, region.x1);
        let (y0, y1) = (self.region.y0, self.region.y1);
        in_bands_with(
            y0..y1,
            width,
            &mut rows[y0 * width..y1 * width],
            padded,
            parallel,
            |band, padded, out| {
                padded.resize(width + kernel.len() - 1, 0.0);
                row_pass(&self.values, width, band, columns, kernel, padded, out);
            },
        );
        out.values.clear();
        out.values.resize(self.values.len(), background);
        out.width = width;
        out.background = background;
        out.region = region;
        let rows = &*rows;
        in_bands(
            region.y0..region.y1,
            width,
            &mut out.values[region.y0 * width..region.y1 * width],
            parallel,
            |band, out| column_pass(rows, width, band, columns, kernel, out),
        );
    }

    /// `self = max(scale · self, floor)` pixel by pixel, in bands of rows across threads when
    /// `parallel`.
    pub(crate) fn scale_at_least(&mut self, scale: f32, floor: &Field, parallel: bool) {
        let background = (scale * self.background).max(floor.background);
        let region = self.region.union(floor.region);
        let width = self.width;
        let height = self.height();
        in_bands(
            0..height,
            width,
            &mut self.values,
            parallel,
            |band, rows| {
                for (y, row) in band.zip(rows.chunks_exact_mut(width)) {
                    if y < region.y0 || y >= region.y1 {
                        row.fill(background);
                        continue;
                    }
                    let floor_row = &floor.values[y * width..(y + 1) * width];
                    row[..region.x0].fill(background);
                    row[region.x1..].fill(background);
                    scale_row_at_least(
                        &mut row[region.x0..region.x1],
                        scale,
                        &floor_row[region.x0..region.x1],
                    );
                }
            },
        );
        self.background = background;
        self.region = region;
    }
}

/// Scratch of [`Field::blur_into`]: the row-filtered image, and a padded row per band.
#[derive(Debug, Clone, Default)]
pub(crate) struct BlurScratch {
    rows: Vec<f32>,
    padded: Vec<Vec<f32>>,
}

/// `value = max(scale · value, floor)` along a row (SIMD-multiversioned; a comparison rather than
/// `f32::max`, whose NaN rule keeps it from vectorising — the values are finite).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn scale_row_at_least(row: &mut [f32], scale: f32, floor: &[f32]) {
    for (value, floor) in row.iter_mut().zip(floor) {
        let scaled = scale * *value;
        *value = if scaled > *floor { scaled } else { *floor };
    }
}

/// The largest of `values` (−∞ for none), in sixteen lanes so that it vectorises (SIMD-
/// multiversioned); the order of comparisons does not change a maximum.
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn max_of(values: &[f32]) -> f32 {
    extreme_of(values, f32::NEG_INFINITY, |value, best| value > best)
}

/// The smallest of `values` (+∞ for none), like [`max_of`].
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn min_of(values: &[f32]) -> f32 {
    extreme_of(values, f32::INFINITY, |value, best| value < best)
}

/// The value of `values` that `better` prefers to all others, `none` if there are none.
#[inline(always)]
fn extreme_of(values: &[f32], none: f32, better: impl Fn(f32, f32) -> bool) -> f32 {
    let pick = |best: f32, value: f32| if better(value, best) { value } else { best };
    let mut lanes = [none; 16];
    let mut chunks = values.chunks_exact(16);
    for chunk in &mut chunks {
        for (lane, value) in lanes.iter_mut().zip(chunk) {
            *lane = pick(*lane, *value);
        }
    }
    let tail = chunks.remainder().iter().copied().fold(none, pick);
    lanes.iter().copied().fold(tail, pick)
}

/// The smallest rectangle holding every pixel of a `width`-wide image that differs from
/// `background` (SIMD-multiversioned: rows are scanned in blocks without early exits, so that
/// the comparisons vectorise).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn region_of(values: &[f32], width: usize, background: f32) -> Region {
    const SCAN: usize = 64;
    let differs = |block: &[f32]| block.iter().fold(false, |any, v| any | (*v != background));
    let mut region = Region::EMPTY;
    for (y, row) in values.chunks_exact(width).enumerate() {
        let blocks = row.len().div_ceil(SCAN);
        let block = |b: usize| &row[b * SCAN..((b + 1) * SCAN).min(row.len())];
        let Some(first_block) = (0..blocks).find(|b| differs(block(*b))) else {
            continue;
        };
        let last_block = (first_block..blocks)
            .rev()
            .find(|b| differs(block(*b)))
            .unwrap_or(first_block);
        let first = block(first_block)
            .iter()
            .position(|v| *v != background)
            .unwrap_or(0);
        let last = block(last_block)
            .iter()
            .rposition(|v| *v != background)
            .unwrap_or(0);
        region = region.union(Region {
            x0: first_block * SCAN + first,
            x1: last_block * SCAN + last + 1,
            y0: y,
            y1: y + 1,
        });
    }
    region
}

/// Whether `kernel` reads the same backwards (the reference's even-sized kernels do not: their
/// centre is off by half a pixel and their folded tails differ).
fn is_symmetric(kernel: &[f32]) -> bool {
    kernel.iter().eq(kernel.iter().rev())
}

/// Columns accumulated at once in registers (four AVX-512 or eight AVX2 registers of f32).
const BLOCK: usize = 64;

/// `out = Σₖ kernel[k] · taps(k)`, element by element, each `taps(k)` as long as `out`; a
/// symmetric kernel pairs tap k with tap n − 1 − k, halving the multiplications. Blocks of
/// [`BLOCK`] columns are summed in registers over every tap before they are stored; each element
/// is summed in the same order either way.
#[inline(always)]
fn accumulate<'a>(out: &mut [f32], kernel: &[f32], taps: impl Fn(usize) -> &'a [f32]) {
    let symmetric = is_symmetric(kernel);
    let full = out.len() / BLOCK * BLOCK;
    for start in (0..full).step_by(BLOCK) {
        let block = |k: usize| -> &'a [f32; BLOCK] {
            let tap: &'a [f32] = taps(k);
            tap[start..start + BLOCK]
                .try_into()
                .expect("a block is BLOCK long")
        };
        let mut sums = [0.0f32; BLOCK];
        accumulate_into(&mut sums, kernel, symmetric, block);
        out[start..start + BLOCK].copy_from_slice(&sums);
    }
    let tail = &mut out[full..];
    tail.fill(0.0);
    accumulate_into(tail, kernel, symmetric, |k| &taps(k)[full..]);
}

/// `out += Σₖ kernel[k] · taps(k)`, tap by tap.
#[inline(always)]
fn accumulate_into<'a, T: AsRef<[f32]> + ?Sized + 'a>(
    out: &mut [f32],
    kernel: &[f32],
    symmetric: bool,
    taps: impl Fn(usize) -> &'a T,
) {
    let n = kernel.len();
    if !symmetric {
        for (k, weight) in kernel.iter().enumerate() {
            for (value, sample) in out.iter_mut().zip(taps(k).as_ref()) {
                *value += weight * sample;
            }
        }
        return;
    }
    for (k, weight) in kernel[..n / 2].iter().enumerate() {
        let pairs = taps(k).as_ref().iter().zip(taps(n - 1 - k).as_ref());
        for (value, (a, b)) in out.iter_mut().zip(pairs) {
            *value += weight * (a + b);
        }
    }
    if n % 2 == 1 {
        for (value, sample) in out.iter_mut().zip(taps(n / 2).as_ref()) {
            *value += kernel[n / 2] * sample;
        }
    }
}

/// Row correlation of `rows`, written for columns `x0..x1` into `out` (those rows;
/// SIMD-multiversioned).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn row_pass(
    values: &[f32],
    width: usize,
    rows: Range<usize>,
    (x0, x1): (usize, usize),
    kernel: &[f32],
    padded: &mut [f32],
    out: &mut [f32],
) {
    let anchor = kernel.len() / 2;
    for (y, out) in rows.zip(out.chunks_exact_mut(width)) {
        pad_reflect_101(&values[y * width..(y + 1) * width], anchor, padded);
        let padded = &*padded;
        accumulate(&mut out[x0..x1], kernel, |k| &padded[x0 + k..x1 + k]);
    }
}

/// Column correlation of `source` for `rows` and columns `x0..x1`, into `out` (those rows;
/// SIMD-multiversioned).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn column_pass(
    source: &[f32],
    width: usize,
    rows: Range<usize>,
    (x0, x1): (usize, usize),
    kernel: &[f32],
    out: &mut [f32],
) {
    let height = source.len() / width;
    let anchor = kernel.len() / 2;
    for (y, out) in rows.zip(out.chunks_exact_mut(width)) {
        let interior = y >= anchor && y + kernel.len() - anchor <= height;
        let taps = |k: usize| {
            let row = if interior {
                y + k - anchor
            } else {
                reflect_101(y as i64 + k as i64 - anchor as i64, height as i64)
            };
            &source[row * width + x0..row * width + x1]
        };
        accumulate(&mut out[x0..x1], kernel, taps);
    }
}

#[cfg(test)]
mod tests {
    use super::{BlurScratch, Field, Region};
    use crate::tactile::filter::{gaussian_kernel, reflect_101};

    /// The correlation with `kernel ⊗ kernel` computed directly, tap by tap over the 2-D window,
    /// in f64.
    fn direct_blur(values: &[f32], width: usize, kernel: &[f64]) -> Vec<f64> {
        let (height, anchor) = (values.len() / width, kernel.len() as i64 / 2);
        let mut out = vec![0.0; values.len()];
        for (i, value) in out.iter_mut().enumerate() {
            let (x, y) = ((i % width) as i64, (i / width) as i64);
            for (j, kj) in kernel.iter().enumerate() {
                let row = reflect_101(y + j as i64 - anchor, height as i64);
                for (k, kk) in kernel.iter().enumerate() {
                    let column = reflect_101(x + k as i64 - anchor, width as i64);
                    *value += kj * kk * f64::from(values[row * width + column]);
                }
            }
        }
        out
    }

    #[test]
    fn the_region_holds_exactly_the_pixels_off_the_background() {
        let (width, height) = (150, 5);
        for (xs, y) in [
            (vec![63], 0),
            (vec![64], 4),
            (vec![0, 149], 2),
            (vec![65, 127, 128], 1),
        ] {
            let mut values = vec![0.5f32; width * height];
            for &x in &xs {
                values[y * width + x] = 0.75;
            }
            let mut field = Field::empty();
            field.assign(width, values.into_iter());
            let expected = Region {
                x0: xs[0],
                x1: xs[xs.len() - 1] + 1,
                y0: y,
                y1: y + 1,
            };
            assert_eq!((field.region, field.background), (expected, 0.5), "{xs:?}");
        }
        let mut flat = Field::empty();
        flat.assign(width, std::iter::repeat_n(0.25, width * height));
        assert!(flat.region.is_empty());
        assert_eq!(flat.max(), 0.25);
    }

    #[test]
    fn sparse_blur_equals_the_direct_one() {
        let (width, height) = (60, 40);
        for (cx, cy) in [(30, 20), (2, 3), (57, 38)] {
            let values: Vec<f32> = (0..width * height)
                .map(|i| {
                    let (x, y) = ((i % width) as f32, (i / width) as f32);
                    let r2 = (x - cx as f32).powi(2) + (y - cy as f32).powi(2);
                    0.25 + if r2 < 16.0 { (16.0 - r2) / 10.0 } else { 0.0 }
                })
                .collect();
            for (n, sigma) in [(21, 7.0), (52, 9.0)] {
                let kernel = gaussian_kernel(n, sigma);
                let mut field = Field::empty();
                field.assign(width, values.iter().copied());
                let single: Vec<f32> = kernel.iter().map(|k| *k as f32).collect();
                let direct = direct_blur(&values, width, &kernel);
                let mut scratch = BlurScratch::default();
                let mut sparse = Field::empty();
                field.blur_into(&single, &mut scratch, &mut sparse, false);
                for (a, b) in sparse.values.iter().zip(&direct) {
                    assert!(
                        (f64::from(*a) - b).abs() < 1e-5,
                        "{a} vs {b} (centre {cx},{cy}, n {n})"
                    );
                }
                if cfg!(feature = "parallel") {
                    let mut banded = Field::empty();
                    field.blur_into(&single, &mut scratch, &mut banded, true);
                    assert_eq!(banded.values, sparse.values, "bands change the blur");
                }
            }
        }
    }
}
