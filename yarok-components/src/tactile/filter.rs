//! The reference's Gaussian kernels, and OpenCV's default border (reflect-101) that the optical
//! models' filters use.

/// The 1-D factor of the reference's `G(n, σ)` kernel: a unit impulse at `n / 2` smoothed by a
/// Gaussian of `σ` truncated at 4σ with half-sample reflection at the ends (SciPy's
/// `gaussian_filter1d` on an impulse), so the tails fold back and the kernel sums to 1.
pub fn gaussian_kernel(n: usize, sigma: f64) -> Vec<f64> {
    let radius = (4.0 * sigma + 0.5) as i64;
    let weights: Vec<f64> = (-radius..=radius)
        .map(|k| (-0.5 * (k * k) as f64 / (sigma * sigma)).exp())
        .collect();
    let total: f64 = weights.iter().sum();
    let centre = (n / 2) as i64;
    let mut kernel = vec![0.0; n];
    for (i, value) in kernel.iter_mut().enumerate() {
        for (k, weight) in (-radius..=radius).zip(&weights) {
            if reflect(i as i64 + k, n as i64) == centre {
                *value += weight / total;
            }
        }
    }
    kernel
}

/// SciPy's `reflect` border (`dcba|abcd|dcba`).
pub(crate) fn reflect(mut index: i64, len: i64) -> i64 {
    let period = 2 * len;
    index = index.rem_euclid(period);
    if index < len {
        index
    } else {
        period - 1 - index
    }
}

/// Copies `row` into the middle of `padded`, its ends filled by OpenCV's default border
/// (`gfedcb|abcdefgh|gfedcba`): `before` values on the left, the rest on the right.
pub(crate) fn pad_reflect_101<T: Copy>(row: &[T], before: usize, padded: &mut [T]) {
    let width = row.len() as i64;
    padded[before..before + row.len()].copy_from_slice(row);
    for i in 0..before {
        padded[i] = row[reflect_101(i as i64 - before as i64, width)];
    }
    for i in before + row.len()..padded.len() {
        padded[i] = row[reflect_101(i as i64 - before as i64, width)];
    }
}

/// OpenCV's default border (`gfedcb|abcdefgh|gfedcba`), for images at least 2 pixels wide.
pub(crate) fn reflect_101(index: i64, len: i64) -> usize {
    if len == 1 {
        return 0;
    }
    let period = 2 * (len - 1);
    let index = index.rem_euclid(period);
    (if index < len { index } else { period - index }) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernels_match_the_reference_vectors() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../tests/golden/tactile/gaussian_kernels.json"
        );
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
        let reference: serde_json::Value = serde_json::from_str(&text).unwrap();
        for (name, n, sigma) in [
            ("gkern2_21_7", 21, 7.0),
            ("gkern2_52_9", 52, 9.0),
            ("gkern2_3_1", 3, 1.0),
            ("gkern2_95_9", 95, 9.0),
        ] {
            let expected: Vec<f64> = reference[name]["k1"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            let ours = gaussian_kernel(n, sigma);
            assert_eq!(ours.len(), expected.len(), "{name}");
            for (a, b) in ours.iter().zip(&expected) {
                assert!((a - b).abs() < 1e-15, "{name}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn borders_reflect_like_opencv() {
        assert_eq!(
            [-2, -1, 0, 3, 4, 5].map(|i| reflect_101(i, 4)),
            [2, 1, 0, 3, 2, 1]
        );
        let mut padded = [0; 8];
        pad_reflect_101(&[1, 2, 3, 4], 2, &mut padded);
        assert_eq!(padded, [3, 2, 1, 2, 3, 4, 3, 2]);
    }
}
