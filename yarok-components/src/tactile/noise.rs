//! Seeded Gaussian noise, so that simulated textures and cameras' noise are reproducible.

/// A SplitMix64 generator: small, fast and the same on every platform.
#[derive(Debug, Clone)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in [`lower`, `upper`).
    pub fn uniform(&mut self, lower: f64, upper: f64) -> f64 {
        lower + (upper - lower) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A uniform number in (0, 1].
    fn unit(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 1.0) / (1u64 << 53) as f64
    }

    /// `count` samples of N(0, sigma²), by the Box–Muller transform.
    pub fn normal(&mut self, count: usize, sigma: f64) -> Vec<f64> {
        let mut samples = Vec::with_capacity(count + 1);
        while samples.len() < count {
            let (u, v) = (self.unit(), self.unit());
            let radius = sigma * (-2.0 * u.ln()).sqrt();
            let angle = std::f64::consts::TAU * v;
            samples.push(radius * angle.cos());
            samples.push(radius * angle.sin());
        }
        samples.truncate(count);
        samples
    }
}

/// A camera's noise as a pattern drawn from a seed: per value of an RGB frame, a normal sample of
/// its channel's level. A sensor adds one fixed pattern to every frame (as the reference model's
/// gel texture is fixed), so that a frame depends on what presses alone; a fresh seed per image
/// gives fresh noise.
///
/// ```
/// use yarok_components::tactile::noise::CameraNoise;
///
/// let noise = CameraNoise::new([2.0, 2.0, 3.0], 4 * 3, 7);
/// let mut frame = [100u8; 4 * 3];
/// noise.add(&mut frame);
/// assert_ne!(frame, [100; 12]);
/// let mut again = [100u8; 4 * 3];
/// CameraNoise::new([2.0, 2.0, 3.0], 4 * 3, 7).add(&mut again);
/// assert_eq!(frame, again);
/// ```
#[derive(Debug, Clone)]
pub struct CameraNoise {
    /// Per value of a frame (RGB): the noise, levels.
    pattern: Vec<f32>,
}

impl CameraNoise {
    /// The noise of `values` values (pixels × 3) of a camera whose channels' noise has the
    /// standard deviations `levels` (R, G, B; levels), drawn from `seed`.
    pub fn new(levels: [f64; 3], values: usize, seed: u64) -> Self {
        let samples = SplitMix64::new(seed).normal(values, 1.0);
        let pattern = samples
            .iter()
            .enumerate()
            .map(|(index, sample)| (sample * levels[index % 3]) as f32)
            .collect();
        Self { pattern }
    }

    /// Adds the noise to `pixels` (RGB), rounding and clamping to 0-255.
    pub fn add(&self, pixels: &mut [u8]) {
        for (pixel, noise) in pixels.iter_mut().zip(&self.pattern) {
            *pixel = (f32::from(*pixel) + noise + 0.5).clamp(0.0, 255.0) as u8;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::SplitMix64;

    #[test]
    fn samples_are_reproducible_and_normal() {
        let a = SplitMix64::new(7).normal(20_000, 2.0);
        assert_eq!(a, SplitMix64::new(7).normal(20_000, 2.0));
        assert_ne!(a, SplitMix64::new(8).normal(20_000, 2.0));
        let mean = a.iter().sum::<f64>() / a.len() as f64;
        let sd = (a.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / a.len() as f64).sqrt();
        assert!(
            mean.abs() < 0.05 && (sd - 2.0).abs() < 0.05,
            "mean {mean}, sd {sd}"
        );
    }
}
