//! The Phong model of DIGIT and GelSight sensors: a depth map of the elastomer's inside, in,
//! a sensor image, out (the published simulation of Gomes et al. and its DIGIT port).

use super::field::Field;
use super::filter::{correlate_columns, correlate_rows, gaussian_blur, gaussian_kernel};

/// A coloured light of the Phong model.
#[derive(Debug, Clone, PartialEq)]
pub struct PhongLight {
    /// Direction towards the light (not normalised, as in the reference).
    pub position: [f64; 3],
    /// Colour, RGB 0–255.
    pub colour: [f64; 3],
    /// Diffuse coefficient.
    pub kd: f64,
    /// Specular coefficient.
    pub ks: f64,
    /// Specular exponent.
    pub alpha: i32,
}

/// Parameters of the Phong model, the reference's defaults per sensor in [`PhongParams::digit`]
/// and [`PhongParams::gelsight2014`].
#[derive(Debug, Clone, PartialEq)]
pub struct PhongParams {
    /// Lights, blended in order.
    pub lights: Vec<PhongLight>,
    /// Ambient coefficient applied to the background.
    pub ka: f64,
    /// Metres per pixel of the depth map.
    pub px2m_ratio: f64,
    /// Elastomer thickness, in the depth's unit.
    pub elastomer_thickness: f64,
    /// Depth of the elastomer's inner surface, in the depth's unit.
    pub min_depth: f64,
    /// Smoothing iterations of the elastic deformation.
    pub iterations: usize,
    /// Extra deformation passes on the wide kernel (GelSight).
    pub extra_passes: bool,
    /// Standard deviation of the gel's texture noise added to the deformed depth (depth unit);
    /// 0 turns it off.
    pub texture_sigma: f64,
    /// Seed of the texture noise: the same seed gives the same texture, byte for byte.
    pub seed: u64,
}

fn light(position: [f64; 3], colour: [f64; 3], kd: f64, ks: f64) -> PhongLight {
    PhongLight {
        position,
        colour,
        kd,
        ks,
        alpha: 5,
    }
}

impl PhongParams {
    /// DIGIT (320 rows × 240 columns), fed the raw z-buffer as the reference does: thickness 1,
    /// minimum depth 0, three lights at 120°.
    pub fn digit() -> Self {
        Self {
            lights: vec![
                light([-0.866, 0.5, 0.25], [255.0, 82.0, 108.0], 0.1, 0.4),
                light([0.866, 0.5, 0.25], [153.0, 255.0, 120.0], 0.1, 0.4),
                light([0.0, -1.0, 0.25], [115.0, 130.0, 255.0], 0.3, 0.4),
            ],
            ka: 1.0,
            px2m_ratio: 5.4347826087e-05,
            elastomer_thickness: 1.0,
            min_depth: 0.0,
            iterations: 3,
            extra_passes: false,
            texture_sigma: 1e-5,
            seed: 0,
        }
    }

    /// GelSight 2014 (480 × 640), depth in metres: gel from 0.030 to 0.034 m, four lights.
    pub fn gelsight2014() -> Self {
        Self {
            lights: vec![
                light([0.0, 1.0, 0.25], [255.0, 255.0, 255.0], 0.6, 0.5),
                light([-1.0, 0.0, 0.25], [115.0, 130.0, 255.0], 0.5, 0.3),
                light([0.0, -1.0, 0.25], [255.0, 82.0, 108.0], 0.6, 0.4),
                light([1.0, 0.0, 0.25], [153.0, 255.0, 120.0], 0.1, 0.1),
            ],
            ka: 0.8,
            px2m_ratio: 5.4347826087e-05,
            elastomer_thickness: 0.004,
            min_depth: 0.03,
            iterations: 3,
            extra_passes: true,
            texture_sigma: 2e-6,
            seed: 0,
        }
    }

    fn max_depth(&self) -> f64 {
        self.min_depth + self.elastomer_thickness
    }
}

/// The Phong optical model, with its kernels built once.
#[derive(Debug, Clone)]
pub struct PhongModel {
    params: PhongParams,
    narrow: Vec<f32>,
    wide: Vec<f32>,
    blur: Vec<f64>,
}

impl PhongModel {
    /// A model with these parameters.
    pub fn new(params: PhongParams) -> Self {
        let single = |kernel: Vec<f64>| kernel.into_iter().map(|k| k as f32).collect();
        Self {
            params,
            narrow: single(gaussian_kernel(21, 7.0)),
            wide: single(gaussian_kernel(52, 9.0)),
            blur: gaussian_kernel(3, 1.0),
        }
    }

    /// Renders the sensor image for `depth` (`height × width`, row-major, in the parameters'
    /// unit) over `background` (RGB, `height × width × 3`). Returns RGB, `height × width × 3`.
    ///
    /// # Panics
    ///
    /// When `depth` and `background` sizes do not match `width`.
    pub fn render(&self, depth: &[f32], width: usize, background: &[u8]) -> Vec<u8> {
        assert_eq!(
            depth.len() * 3,
            background.len(),
            "background must be width × height × 3"
        );
        assert_eq!(depth.len() % width, 0, "depth must be width × height");
        let p = &self.params;
        let max_depth = p.max_depth();
        let protrusion: Vec<f64> = depth
            .iter()
            .map(|&d| {
                if f64::from(d) >= max_depth {
                    max_depth
                } else {
                    f64::from(d)
                }
            })
            .collect();
        let elastomer = self.deform(&protrusion, width, max_depth);

        let mut out: Vec<u8> = background
            .iter()
            .enumerate()
            .map(|(i, &b)| {
                let shadow =
                    ((max_depth - protrusion[i / 3]) / p.elastomer_thickness).clamp(0.0, 1.0);
                overlay(p.ka * f64::from(b), shadow, 0.0)
            })
            .collect();

        let noise = if p.texture_sigma > 0.0 {
            super::noise::SplitMix64::new(p.seed).normal(elastomer.len(), p.texture_sigma)
        } else {
            vec![0.0; elastomer.len()]
        };
        let scaled: Vec<f64> = elastomer
            .iter()
            .zip(&noise)
            .map(|(e, n)| (e + n) / p.px2m_ratio)
            .collect();
        let normals = normals(&scaled, width);
        for light in &p.lights {
            for (pixel, n) in normals.iter().enumerate() {
                let dot =
                    n[0] * light.position[0] + n[1] * light.position[1] + n[2] * light.position[2];
                let diffuse = (light.kd * dot).max(0.0);
                let reflected_z = 2.0 * dot * n[2] - light.position[2];
                let intensity = diffuse + light.ks * reflected_z.powi(light.alpha);
                for c in 0..3 {
                    let value = &mut out[3 * pixel + c];
                    *value = overlay(f64::from(*value), intensity, light.colour[c]);
                }
            }
        }
        self.final_blur(&out, width)
    }

    /// Elastic deformation: the indentation smoothed by two Gaussians (difference of Gaussians),
    /// each iteration renormalised to keep the indentation's peak. Runs in f32 like the reference,
    /// on the part of the image a press changes.
    fn deform(&self, protrusion: &[f64], width: usize, max_depth: f64) -> Vec<f64> {
        let indentation = Field::new(
            protrusion.iter().map(|p| (max_depth - p) as f32).collect(),
            width,
        );
        let peak = indentation.max();
        let passes = |kernel: &[f32], start: Field, times: usize| {
            let mut current = start;
            for _ in 0..times {
                let blurred = current.blur(kernel);
                let peak_out = blurred.max();
                let ratio = if peak_out <= 0.0 {
                    1.0
                } else {
                    peak / peak_out
                };
                current = blurred.scaled_at_least(ratio, &indentation);
            }
            current
        };
        let narrow = passes(&self.narrow, indentation.clone(), self.params.iterations);
        let mut wide = passes(&self.wide, indentation.clone(), self.params.iterations);
        if self.params.extra_passes {
            wide = passes(&self.narrow, wide, self.params.iterations);
        }
        narrow
            .values
            .iter()
            .zip(&wide.values)
            .map(|(a, b)| f64::from(max_depth as f32 - (2.0 * a - b)))
            .collect()
    }

    fn final_blur(&self, image: &[u8], width: usize) -> Vec<u8> {
        let pixels = image.len() / 3;
        let mut channel = vec![0.0; pixels];
        let mut scratch = vec![0.0; pixels];
        let mut blurred = vec![0.0; pixels];
        let mut out = vec![0u8; image.len()];
        for c in 0..3 {
            for (i, value) in channel.iter_mut().enumerate() {
                *value = f64::from(image[3 * i + c]);
            }
            gaussian_blur(&channel, width, &self.blur, &mut scratch, &mut blurred);
            for (i, value) in blurred.iter().enumerate() {
                out[3 * i + c] = value.round_ties_even().clamp(0.0, 255.0) as u8;
            }
        }
        out
    }
}

/// `clip((1 − α)·value + α·colour, 0, 255)` truncated to u8, as the reference's overlay.
fn overlay(value: f64, alpha: f64, colour: f64) -> u8 {
    ((1.0 - alpha) * value + alpha * colour).clamp(0.0, 255.0) as u8
}

/// Unit normals `(−∂x, −∂y, 1)/‖·‖` with central differences and reflect-101 borders.
fn normals(height_map: &[f64], width: usize) -> Vec<[f64; 3]> {
    let mut dx = vec![0.0; height_map.len()];
    let mut dy = vec![0.0; height_map.len()];
    correlate_rows(height_map, width, &[-0.5, 0.0, 0.5], &mut dx);
    correlate_columns(height_map, width, &[-0.5, 0.0, 0.5], &mut dy);
    dx.iter()
        .zip(&dy)
        .map(|(x, y)| {
            let norm = (x * x + y * y + 1.0).sqrt();
            [-x / norm, -y / norm, 1.0 / norm]
        })
        .collect()
}
