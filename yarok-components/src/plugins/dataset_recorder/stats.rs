//! Per-feature statistics as LeRobot keeps them (`min`, `max`, `mean`, `std`, `count` and the
//! quantiles `q01` … `q99`), computed exactly: numbers from every value, images from a
//! histogram of every pixel.

use std::collections::BTreeMap;

/// The quantiles LeRobot keeps, as fractions and as the keys it names them by.
const QUANTILES: [(f64, &str); 5] = [
    (0.01, "q01"),
    (0.10, "q10"),
    (0.50, "q50"),
    (0.90, "q90"),
    (0.99, "q99"),
];

/// One feature's statistics: each statistic's values, one per element of the feature (a
/// joint, a colour channel), and the number of samples.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Summary {
    /// `min`, `max`, `mean`, `std` and the quantiles, each with one value per element.
    pub(super) values: BTreeMap<&'static str, Vec<f64>>,
    /// How many samples each element has.
    pub(super) count: u64,
}

impl Summary {
    /// The summary of a feature's elements, each given by its ranked samples.
    fn of<R: Ranked>(elements: &[R]) -> Self {
        let mut values: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
        let mut count = 0;
        for element in elements {
            count = element.len();
            let n = count as f64;
            let mean = element.sum() / n;
            // Two passes: E[x²] − E[x]² cancels catastrophically for a nearly constant element
            // (a block resting at z = 0.4175 m varies by micrometres).
            let variance = element.squared_deviations(mean) / n;
            let ranked = |rank: u64| element.at_rank(rank);
            values.entry("min").or_default().push(ranked(0));
            values
                .entry("max")
                .or_default()
                .push(ranked(count.saturating_sub(1)));
            values.entry("mean").or_default().push(mean);
            values.entry("std").or_default().push(variance.sqrt());
            for (fraction, key) in QUANTILES {
                values
                    .entry(key)
                    .or_default()
                    .push(quantile(count, fraction, ranked));
            }
        }
        Self { values, count }
    }
}

/// The `fraction` quantile of `count` sorted samples, interpolated linearly between the two
/// nearest ranks (numpy's default method).
fn quantile(count: u64, fraction: f64, at_rank: impl Fn(u64) -> f64) -> f64 {
    if count == 0 {
        return f64::NAN;
    }
    let position = fraction * (count - 1) as f64;
    let below = position.floor() as u64;
    let above = position.ceil() as u64;
    let low = at_rank(below);
    low + (at_rank(above) - low) * (position - below as f64)
}

/// Samples that can be ranked: the `rank`-th smallest, their sum and the sum of their squared
/// deviations from a mean.
trait Ranked {
    fn len(&self) -> u64;
    fn sum(&self) -> f64;
    fn squared_deviations(&self, mean: f64) -> f64;
    fn at_rank(&self, rank: u64) -> f64;
}

/// Every value of one element, sorted when summarized.
#[derive(Debug, Clone, Default)]
struct Values(Vec<f64>);

impl Ranked for Values {
    fn len(&self) -> u64 {
        self.0.len() as u64
    }

    fn sum(&self) -> f64 {
        self.0.iter().sum()
    }

    fn squared_deviations(&self, mean: f64) -> f64 {
        self.0.iter().map(|v| (v - mean).powi(2)).sum()
    }

    fn at_rank(&self, rank: u64) -> f64 {
        self.0[rank as usize]
    }
}

/// Numbers of a feature of `width` elements (a vector like the joint positions, or one value
/// like the timestamp), every frame's kept.
#[derive(Debug, Clone)]
pub(super) struct NumberStats {
    elements: Vec<Values>,
}

impl NumberStats {
    /// Statistics of a feature of `width` elements.
    pub(super) fn new(width: usize) -> Self {
        Self {
            elements: vec![Values::default(); width],
        }
    }

    /// Adds one frame's values (`width` of them).
    pub(super) fn add(&mut self, frame: impl IntoIterator<Item = f64>) {
        for (element, value) in self.elements.iter_mut().zip(frame) {
            element.0.push(value);
        }
    }

    /// Adds every frame of `other`.
    pub(super) fn merge(&mut self, other: &Self) {
        for (element, theirs) in self.elements.iter_mut().zip(&other.elements) {
            element.0.extend_from_slice(&theirs.0);
        }
    }

    /// The statistics of the values added.
    pub(super) fn summary(&self) -> Summary {
        let mut sorted = self.elements.clone();
        for element in &mut sorted {
            element.0.sort_by(f64::total_cmp);
        }
        Summary::of(&sorted)
    }
}

/// How many pixels of one colour channel have each of the 256 values.
#[derive(Debug, Clone)]
struct Histogram(Box<[u64; 256]>);

impl Ranked for Histogram {
    fn len(&self) -> u64 {
        self.0.iter().sum()
    }

    fn sum(&self) -> f64 {
        self.0
            .iter()
            .enumerate()
            .map(|(value, count)| value as f64 * *count as f64)
            .sum()
    }

    fn squared_deviations(&self, mean: f64) -> f64 {
        self.0
            .iter()
            .enumerate()
            .map(|(value, count)| (value as f64 - mean).powi(2) * *count as f64)
            .sum()
    }

    fn at_rank(&self, rank: u64) -> f64 {
        let mut seen = 0;
        for (value, count) in self.0.iter().enumerate() {
            seen += count;
            if rank < seen {
                return value as f64;
            }
        }
        255.0
    }
}

/// Every pixel of an RGB video feature, per channel, in LeRobot's unit: values from 0 to 1.
#[derive(Debug, Clone)]
pub(super) struct ImageStats {
    channels: [Histogram; 3],
}

impl Default for ImageStats {
    fn default() -> Self {
        Self {
            channels: std::array::from_fn(|_| Histogram(Box::new([0; 256]))),
        }
    }
}

impl ImageStats {
    /// Adds one frame's pixels, RGB interleaved.
    pub(super) fn add(&mut self, rgb: &[u8]) {
        for pixel in rgb.chunks_exact(3) {
            for (channel, value) in self.channels.iter_mut().zip(pixel) {
                channel.0[usize::from(*value)] += 1;
            }
        }
    }

    /// Adds every pixel of `other`.
    pub(super) fn merge(&mut self, other: &Self) {
        for (channel, theirs) in self.channels.iter_mut().zip(&other.channels) {
            for (count, added) in channel.0.iter_mut().zip(theirs.0.iter()) {
                *count += added;
            }
        }
    }

    /// The statistics of the pixels added, per channel, from 0 to 1; `count` is the number of
    /// frames, as LeRobot counts image samples.
    pub(super) fn summary(&self, frames: u64) -> Summary {
        let mut summary = Summary::of(&self.channels);
        for values in summary.values.values_mut() {
            for value in values {
                *value /= 255.0;
            }
        }
        summary.count = frames;
        summary
    }
}

/// One feature's statistics as they are gathered.
#[derive(Debug, Clone)]
pub(super) enum FeatureStats {
    Numbers(NumberStats),
    /// An image's pixels, and the number of frames.
    Image(ImageStats, u64),
}

impl FeatureStats {
    /// Adds every sample of `other` (a feature of the same kind).
    pub(super) fn merge(&mut self, other: &Self) {
        match (self, other) {
            (Self::Numbers(mine), Self::Numbers(theirs)) => mine.merge(theirs),
            (Self::Image(mine, frames), Self::Image(theirs, more)) => {
                mine.merge(theirs);
                *frames += more;
            }
            _ => {}
        }
    }

    /// The statistics, and whether they are an image's.
    pub(super) fn summary(&self) -> (Summary, bool) {
        match self {
            Self::Numbers(numbers) => (numbers.summary(), false),
            Self::Image(image, frames) => (image.summary(*frames), true),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_summarized_as_numpy_does() {
        let mut stats = NumberStats::new(2);
        for (a, b) in [(3.0, 10.0), (1.0, 10.0), (2.0, 40.0), (4.0, 20.0)] {
            stats.add([a, b]);
        }
        let summary = stats.summary();
        assert_eq!(summary.count, 4);
        assert_eq!(summary.values["min"], [1.0, 10.0]);
        assert_eq!(summary.values["max"], [4.0, 40.0]);
        assert_eq!(summary.values["mean"], [2.5, 20.0]);
        // numpy: np.std([1, 2, 3, 4]) = 1.1180…, np.quantile([1, 2, 3, 4], 0.1) = 1.3.
        assert!((summary.values["std"][0] - 1.118_033_988_749_895).abs() < 1e-12);
        assert!((summary.values["q10"][0] - 1.3).abs() < 1e-12);
        assert_eq!(summary.values["q50"], [2.5, 15.0]);
    }

    #[test]
    fn an_image_histogram_gives_the_stats_of_its_pixels_from_0_to_1() {
        let mut stats = ImageStats::default();
        stats.add(&[0, 255, 51, 255, 255, 51]);
        let mut other = ImageStats::default();
        other.add(&[0, 0, 51]);
        stats.merge(&other);
        let summary = stats.summary(2);
        assert_eq!(summary.count, 2);
        assert_eq!(summary.values["min"], [0.0, 0.0, 0.2]);
        assert_eq!(summary.values["max"], [1.0, 1.0, 0.2]);
        assert_eq!(summary.values["q50"], [0.0, 1.0, 0.2]);
        assert!((summary.values["mean"][0] - 1.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn merged_numbers_are_summarized_as_one_set() {
        let mut first = NumberStats::new(1);
        first.add([1.0]);
        let mut second = NumberStats::new(1);
        second.add([5.0]);
        second.add([3.0]);
        first.merge(&second);
        let summary = first.summary();
        assert_eq!(summary.values["q50"], [3.0]);
        assert_eq!(summary.count, 3);
    }
}
