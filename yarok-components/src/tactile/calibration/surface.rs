//! The gel's surface seen by a calibrated model: how far each pixel of it has sunk (in pixels),
//! spread around the contact as a real gel's surface sinks, and the per-pixel terms of its
//! normal and height that the model's colours are a function of.

/// The terms of the surface's normal `n = (−gx, −gy, 1)/|…|` and height that colour is a
/// polynomial of: `nx, ny, nz − 1`, their products up to the third degree, and the height.
pub const NORMAL_TERMS: [&str; 13] = [
    "nx",
    "ny",
    "nz-1",
    "nx^2",
    "ny^2",
    "nx*ny",
    "nx*(nz-1)",
    "ny*(nz-1)",
    "nx^3",
    "ny^3",
    "nx^2*ny",
    "nx*ny^2",
    "height/20px",
];

/// The terms of the pixel's position (`x`, `y` from the image's centre, in image widths and
/// heights) that each normal term's weight is a polynomial of: the lights differ across the gel.
/// The height term's weight is the first alone (the same everywhere): a gel sunk evenly, as by a
/// flat face, moves away from the camera evenly and changes its image evenly.
pub const POSITION_TERMS: [&str; 6] = ["1", "x", "y", "x^2", "y^2", "x*y"];

/// How many of [`POSITION_TERMS`] normal term `k`'s weight is fitted with (the others' are 0).
pub(super) fn position_terms_of(k: usize) -> usize {
    if NORMAL_TERMS[k].starts_with("height") {
        1
    } else {
        POSITION_TERMS.len()
    }
}

/// The normal terms of a pixel whose surface slopes by `gx`, `gy` (pixels per pixel) at
/// `height` pixels below the untouched gel.
fn normal_terms(gx: f64, gy: f64, height: f64) -> [f64; NORMAL_TERMS.len()] {
    let nz = 1.0 / (1.0 + gx * gx + gy * gy).sqrt();
    let (nx, ny, w) = (-gx * nz, -gy * nz, nz - 1.0);
    [
        nx,
        ny,
        w,
        nx * nx,
        ny * ny,
        nx * ny,
        nx * w,
        ny * w,
        nx * nx * nx,
        ny * ny * ny,
        nx * nx * ny,
        nx * ny * ny,
        height / 20.0,
    ]
}

/// The model works on a grid of half the image's resolution (the spread gel is smooth at that
/// scale), its colour changes interpolated to the image's pixels: a quarter of the work.
pub(super) const HALF: usize = 2;

/// The half-resolution grid's size for a `width × height` image.
pub(super) fn half_size(width: usize, height: usize) -> (usize, usize) {
    (width.div_ceil(HALF), height.div_ceil(HALF))
}

/// The mean of each 2 × 2 block of a row-major `width`-wide map (blocks cut by the edge are the
/// mean of what they hold).
pub(super) fn halve(values: &[f64], width: usize) -> Vec<f64> {
    let mut half = Vec::new();
    halve_into(|index| values[index], values.len(), width, &mut half);
    half
}

/// [`halve`] of the `len` values `value(index)` of a row-major `width`-wide map, into `half`
/// (its memory reused).
pub(super) fn halve_into(
    value: impl Fn(usize) -> f64,
    len: usize,
    width: usize,
    half: &mut Vec<f64>,
) {
    let height = len / width;
    let (half_width, half_height) = half_size(width, height);
    half.clear();
    half.resize(half_width * half_height, 0.0);
    for (index, out) in half.iter_mut().enumerate() {
        let (hx, hy) = (index % half_width, index / half_width);
        let (mut sum, mut count) = (0.0, 0.0);
        for y in HALF * hy..(HALF * hy + HALF).min(height) {
            for x in HALF * hx..(HALF * hx + HALF).min(width) {
                sum += value(y * width + x);
                count += 1.0;
            }
        }
        *out = sum / count;
    }
}

/// Where pixel `x` of a line of the image falls on the half-resolution line of `half_len`
/// points: the two points around it and the weight of the second (bilinear, edges clamped).
pub(super) fn between(x: usize, half_len: usize) -> (usize, usize, f64) {
    on_half_line(x as f64 + 0.5, half_len)
}

/// [`between`] for any position `at` along a line of the image (pixels from its start; pixel
/// `x`'s centre is at `x + 0.5`).
pub(super) fn on_half_line(at: f64, half_len: usize) -> (usize, usize, f64) {
    let at = (at / HALF as f64 - 0.5).clamp(0.0, (half_len - 1) as f64);
    let first = at.floor() as usize;
    (first, (first + 1).min(half_len - 1), at - first as f64)
}

/// A rectangle of the gel, in the position terms' coordinates (`x`, `y` from the image's centre,
/// in image widths and heights): `[x_min, y_min, x_max, y_max]`.
pub type Area = [f64; 4];

/// The whole plane: positions taken as they are.
pub(super) const EVERYWHERE: Area = [
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
    f64::INFINITY,
    f64::INFINITY,
];

/// Image point (`x`, `y`, pixels from the top-left corner) of a `width × height` image in the
/// position terms' coordinates.
pub(super) fn position(x: f64, y: f64, width: usize, height: usize) -> [f64; 2] {
    [
        (x - width as f64 / 2.0) / width as f64,
        (y - height as f64 / 2.0) / height as f64,
    ]
}

/// The position terms of point (`hx`, `hy`) of the half-resolution grid of a `width × height`
/// image: those of the image's point at its centre, or, outside `covered` (where no calibration
/// press reached), of the nearest point within it — the polynomial is not extrapolated.
pub(super) fn half_position_terms(
    hx: usize,
    hy: usize,
    width: usize,
    height: usize,
    covered: &Area,
) -> [f64; 6] {
    let x = (HALF * hx) as f64 + 0.5 * (HALF - 1) as f64;
    let y = (HALF * hy) as f64 + 0.5 * (HALF - 1) as f64;
    let [x, y] = position(x, y, width, height);
    let x = x.clamp(covered[0], covered[2]);
    let y = y.clamp(covered[1], covered[3]);
    [1.0, x, y, x * x, y * y, x * y]
}

/// The normal terms of each point of a spread half-resolution height map (heights in the image's
/// pixels), `None` where the gel is untouched (flat and not sunk).
pub(super) fn half_normal_terms(
    heights: &[f64],
    half_width: usize,
) -> Vec<Option<[f64; NORMAL_TERMS.len()]>> {
    let mut terms = vec![None; heights.len()];
    for_each_normal_terms(heights, half_width, |index, point| {
        terms[index] = Some(point)
    });
    terms
}

/// Below how many pixels of sinking and of slope (pixels per pixel) the gel counts as untouched:
/// the spread's running sums leave traces of rounding far from any contact, and a colour change
/// this small never moves a pixel's level.
const UNTOUCHED: f64 = 1e-9;

/// Calls `each(index, terms)` with the normal terms of every point of a spread half-resolution
/// height map where the gel is touched (sunk or sloping).
pub(super) fn for_each_normal_terms(
    heights: &[f64],
    half_width: usize,
    mut each: impl FnMut(usize, [f64; NORMAL_TERMS.len()]),
) {
    for_each_slope(heights, half_width, |index, gx, gy| {
        if heights[index].abs() > UNTOUCHED || gx.abs() > UNTOUCHED || gy.abs() > UNTOUCHED {
            // Slopes per half-resolution step, made per image pixel.
            let (gx, gy) = (gx / HALF as f64, gy / HALF as f64);
            each(index, normal_terms(gx, gy, heights[index]));
        }
    });
}

/// Calls `each(index, slope_x, slope_y)` for every pixel of a row-major height map, slopes by
/// central differences (one-sided at the edges).
fn for_each_slope(heights: &[f64], width: usize, mut each: impl FnMut(usize, f64, f64)) {
    let rows = heights.len() / width;
    let difference = |before: usize, after: usize, step: usize| {
        (heights[after] - heights[before]) / ((after - before) / step) as f64
    };
    for y in 0..rows {
        for x in 0..width {
            let index = y * width + x;
            let gx = if width < 2 {
                0.0
            } else {
                let before = if x == 0 { index } else { index - 1 };
                let after = if x + 1 == width { index } else { index + 1 };
                difference(before, after, 1)
            };
            let gy = if rows < 2 {
                0.0
            } else {
                let before = if y == 0 { index } else { index - width };
                let after = if y + 1 == rows { index } else { index + width };
                difference(before, after, width)
            };
            each(index, gx, gy);
        }
    }
}

/// Smooths a row-major map in place by three box filters in each direction, which approximate
/// a Gaussian of `sigma` pixels (edges repeated): how the gel around a contact sinks with it.
pub(super) fn spread(values: &mut [f64], width: usize, sigma: f64) {
    spread_with(values, width, sigma, &mut Vec::new());
}

/// [`spread`] with `scratch` for its intermediate rows (its memory reused).
pub(super) fn spread_with(values: &mut [f64], width: usize, sigma: f64, scratch: &mut Vec<f64>) {
    if sigma <= 0.0 || values.is_empty() || width == 0 {
        return;
    }
    scratch.clear();
    scratch.resize(values.len() + width, 0.0);
    let (rows, sums) = scratch.split_at_mut(values.len());
    for radius in box_radii(sigma) {
        for (row, out) in values.chunks(width).zip(rows.chunks_mut(width)) {
            box_row(row, radius, out);
        }
        box_columns(rows, width, radius, sums, values);
    }
}

/// The radii of three box filters whose succession has the variance of a Gaussian of `sigma`
/// (widths odd, as near each other as possible).
fn box_radii(sigma: f64) -> [usize; 3] {
    let ideal = (12.0 * sigma * sigma / 3.0 + 1.0).sqrt();
    let mut lower = ideal.floor() as i64;
    if lower % 2 == 0 {
        lower -= 1;
    }
    let lower = lower.max(1);
    let upper = lower + 2;
    let at_lower = ((12.0 * sigma * sigma - (3 * lower * lower) as f64 - (12 * lower) as f64 - 9.0)
        / (-4 * lower - 4) as f64)
        .round() as i64;
    std::array::from_fn(|i| ((if (i as i64) < at_lower { lower } else { upper } - 1) / 2) as usize)
}

/// The moving average of `2·radius + 1` values of `row` (edges repeated) into `out`.
fn box_row(row: &[f64], radius: usize, out: &mut [f64]) {
    let len = row.len() as i64;
    let at = |i: i64| row[i.clamp(0, len - 1) as usize];
    let radius = radius as i64;
    let width = (2 * radius + 1) as f64;
    let mut sum: f64 = (-radius..=radius).map(at).sum();
    for (i, out) in out.iter_mut().enumerate() {
        let i = i as i64;
        *out = sum / width;
        sum += at(i + radius + 1) - at(i - radius);
    }
}

/// The moving average of `2·radius + 1` rows of the row-major `values` (edges repeated) into
/// `out`, whole rows at a time, summing in `sum` (a row's length).
fn box_columns(values: &[f64], width: usize, radius: usize, sum: &mut [f64], out: &mut [f64]) {
    let rows = (values.len() / width) as i64;
    let row = |i: i64| {
        let i = i.clamp(0, rows - 1) as usize;
        &values[i * width..(i + 1) * width]
    };
    let radius = radius as i64;
    let scale = 1.0 / (2 * radius + 1) as f64;
    sum.fill(0.0);
    for i in -radius..=radius {
        for (sum, value) in sum.iter_mut().zip(row(i)) {
            *sum += value;
        }
    }
    for (y, out) in out.chunks_mut(width).enumerate() {
        let y = y as i64;
        for (out, sum) in out.iter_mut().zip(sum.iter()) {
            *out = sum * scale;
        }
        for ((sum, added), removed) in sum.iter_mut().zip(row(y + radius + 1)).zip(row(y - radius))
        {
            *sum += added - removed;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spreading_keeps_the_volume_and_has_the_gaussians_width() {
        let (width, sigma) = (201, 6.0);
        let mut values = vec![0.0; width * width];
        values[100 * width + 100] = 1.0;
        spread(&mut values, width, sigma);
        let total: f64 = values.iter().sum();
        assert!((total - 1.0).abs() < 1e-9, "{total}");
        let variance: f64 = (0..width)
            .map(|x| values[100 * width + x] * ((x as f64 - 100.0).powi(2)))
            .sum::<f64>()
            / (0..width).map(|x| values[100 * width + x]).sum::<f64>();
        assert!(
            (variance.sqrt() - sigma).abs() < 0.3,
            "σ = {}",
            variance.sqrt()
        );
    }

    #[test]
    fn a_flat_surface_has_no_normal_terms_but_its_height() {
        let terms = normal_terms(0.0, 0.0, 4.0);
        assert!(terms[..12].iter().all(|t| *t == 0.0));
        assert_eq!(terms[12], 0.2);
    }
}
