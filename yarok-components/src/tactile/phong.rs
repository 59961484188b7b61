//! The Phong model of DIGIT and GelSight sensors: a depth map of the elastomer's inside, in,
//! a sensor image, out (the published simulation of Gomes et al. and its DIGIT port).

use multiversion::multiversion;

use super::field::Field;
use super::filter::{gaussian_blur, gaussian_kernel};
use super::int_pow;

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

    /// DIGIT fed metric depth (metres) instead of the raw z-buffer: the gel's outer surface at
    /// 0.030 m from the camera and 2 mm thick, so only what presses into the gel counts as
    /// contact. The reference's raw mode makes the look depend on the world's near/far planes;
    /// this mode does not.
    pub fn digit_metric() -> Self {
        Self {
            elastomer_thickness: 0.002,
            min_depth: 0.028,
            ..Self::digit()
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

/// The Phong optical model, with its kernels built once and its buffers reused from frame to
/// frame (no allocation per frame once the image size is known).
#[derive(Debug, Clone)]
pub struct PhongModel {
    params: PhongParams,
    narrow: Vec<f32>,
    wide: Vec<f32>,
    blur: Vec<f64>,
    scratch: Scratch,
}

/// Buffers of one image size.
#[derive(Debug, Clone)]
struct Scratch {
    indentation: Field,
    narrow: Field,
    wide: Field,
    blurred: Field,
    rows: Vec<f32>,
    padded: Vec<f32>,
    shadow: Vec<f64>,
    height_map: Vec<f64>,
    noise: Vec<f64>,
    dx: Vec<f64>,
    dy: Vec<f64>,
    nz: Vec<f64>,
    channels: [Vec<f64>; 3],
    channel_rows: Vec<f64>,
    blurred_channels: [Vec<f64>; 3],
}

impl Scratch {
    fn new() -> Self {
        Self {
            indentation: Field::empty(),
            narrow: Field::empty(),
            wide: Field::empty(),
            blurred: Field::empty(),
            rows: Vec::new(),
            padded: Vec::new(),
            shadow: Vec::new(),
            height_map: Vec::new(),
            noise: Vec::new(),
            dx: Vec::new(),
            dy: Vec::new(),
            nz: Vec::new(),
            channels: [Vec::new(), Vec::new(), Vec::new()],
            channel_rows: Vec::new(),
            blurred_channels: [Vec::new(), Vec::new(), Vec::new()],
        }
    }
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
            scratch: Scratch::new(),
        }
    }

    /// Renders the sensor image for `depth` (`height × width`, row-major, in the parameters'
    /// unit) over `background` (RGB, `height × width × 3`). Returns RGB, `height × width × 3`.
    ///
    /// # Panics
    ///
    /// When `depth` and `background` sizes do not match `width`.
    pub fn render(&mut self, depth: &[f32], width: usize, background: &[u8]) -> Vec<u8> {
        let mut out = vec![0; background.len()];
        self.render_into(depth, width, background, &mut out);
        out
    }

    /// [`PhongModel::render`] into a caller's buffer (`height × width × 3`).
    ///
    /// # Panics
    ///
    /// When the sizes do not match.
    pub fn render_into(&mut self, depth: &[f32], width: usize, background: &[u8], out: &mut [u8]) {
        assert_eq!(
            depth.len() * 3,
            background.len(),
            "background must be width × height × 3"
        );
        assert_eq!(
            out.len(),
            background.len(),
            "output must be width × height × 3"
        );
        assert_eq!(depth.len() % width, 0, "depth must be width × height");
        let max_depth = self.params.max_depth();
        let thickness = self.params.elastomer_thickness;
        let s = &mut self.scratch;
        s.shadow.clear();
        s.shadow.extend(
            depth
                .iter()
                .map(|&d| ((max_depth - f64::from(d).min(max_depth)) / thickness).clamp(0.0, 1.0)),
        );
        s.indentation.assign(
            width,
            depth
                .iter()
                .map(|&d| (max_depth - f64::from(d).min(max_depth)) as f32),
        );
        self.deform(max_depth);
        self.light(width, background);
        self.final_blur(width, out);
    }

    /// Elastic deformation: the indentation smoothed by two Gaussians (difference of Gaussians),
    /// each iteration renormalised to keep the indentation's peak. Runs in f32 like the reference,
    /// on the part of the image a press changes. Leaves `height_map` = elastomer depth + texture,
    /// in pixels.
    fn deform(&mut self, max_depth: f64) {
        let s = &mut self.scratch;
        let p = &self.params;
        let peak = s.indentation.max();
        let mut passes = |kernel: &[f32], field: &mut Field, times: usize| {
            for _ in 0..times {
                field.blur_into(kernel, &mut s.rows, &mut s.padded, &mut s.blurred);
                let peak_out = s.blurred.max();
                let ratio = if peak_out <= 0.0 {
                    1.0
                } else {
                    peak / peak_out
                };
                s.blurred.scale_at_least(ratio, &s.indentation);
                std::mem::swap(field, &mut s.blurred);
            }
        };
        s.narrow.copy_from(&s.indentation);
        passes(&self.narrow, &mut s.narrow, p.iterations);
        s.wide.copy_from(&s.indentation);
        passes(&self.wide, &mut s.wide, p.iterations);
        if p.extra_passes {
            passes(&self.narrow, &mut s.wide, p.iterations);
        }
        if s.noise.len() != s.narrow.values.len() {
            s.noise = if p.texture_sigma > 0.0 {
                super::noise::SplitMix64::new(p.seed).normal(s.narrow.values.len(), p.texture_sigma)
            } else {
                vec![0.0; s.narrow.values.len()]
            };
        }
        s.height_map.clear();
        s.height_map.extend(
            s.narrow
                .values
                .iter()
                .zip(&s.wide.values)
                .zip(&s.noise)
                .map(|((a, b), n)| {
                    (f64::from(max_depth as f32 - (2.0 * a - b)) + n) / p.px2m_ratio
                }),
        );
    }

    /// The ambient background darkened by the internal shadow, then each light blended in;
    /// planar, one pass per light, so that the per-pixel work vectorises.
    fn light(&mut self, width: usize, background: &[u8]) {
        let s = &mut self.scratch;
        let p = &self.params;
        let pixels = s.height_map.len();
        s.dx.resize(pixels, 0.0);
        s.dy.resize(pixels, 0.0);
        s.nz.resize(pixels, 0.0);
        normals(&s.height_map, width, [&mut s.dx, &mut s.dy, &mut s.nz]);
        for (c, channel) in s.channels.iter_mut().enumerate() {
            channel.resize(pixels, 0.0);
            shade_channel(channel, background, c, p.ka, &s.shadow);
        }
        let [red, green, blue] = &mut s.channels;
        for light in &p.lights {
            light_pass([&s.dx, &s.dy, &s.nz], [red, green, blue], light);
        }
    }

    fn final_blur(&mut self, width: usize, out: &mut [u8]) {
        let s = &mut self.scratch;
        let pixels = s.channels[0].len();
        s.channel_rows.resize(pixels, 0.0);
        for channel in &mut s.blurred_channels {
            channel.resize(pixels, 0.0);
        }
        for (channel, blurred) in s.channels.iter().zip(&mut s.blurred_channels) {
            gaussian_blur(channel, width, &self.blur, &mut s.channel_rows, blurred);
        }
        let [red, green, blue] = &s.blurred_channels;
        store_pixels([red, green, blue], out);
    }
}

/// Unit normals `(−∂x, −∂y, 1)/‖·‖` of a height map, with central differences and OpenCV's
/// reflect-101 border (so the derivative across an edge is zero).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn normals(height_map: &[f64], width: usize, [nx, ny, nz]: [&mut [f64]; 3]) {
    let height = height_map.len() / width;
    for y in 0..height {
        let row = &height_map[y * width..(y + 1) * width];
        // Reflect-101 rows: above the first row is the second, below the last the one before it.
        let above_index = if y == 0 { 1.min(height - 1) } else { y - 1 };
        let below_index = if y + 1 < height {
            y + 1
        } else {
            height.saturating_sub(2)
        };
        let above = &height_map[above_index * width..(above_index + 1) * width];
        let below = &height_map[below_index * width..(below_index + 1) * width];
        let out = y * width..(y + 1) * width;
        let (rx, ry, rz) = (&mut nx[out.clone()], &mut ny[out.clone()], &mut nz[out]);
        for (x, dx) in rx.iter_mut().enumerate() {
            let left = if x == 0 { 1.min(width - 1) } else { x - 1 };
            let right = if x + 1 < width {
                x + 1
            } else {
                width.saturating_sub(2)
            };
            *dx = (row[right] - row[left]) / 2.0;
        }
        let slopes = rx.iter_mut().zip(ry.iter_mut()).zip(rz.iter_mut());
        for (((dx, dy), dz), (a, b)) in slopes.zip(above.iter().zip(below)) {
            *dy = (b - a) / 2.0;
            let norm = (*dx * *dx + *dy * *dy + 1.0).sqrt();
            (*dx, *dy, *dz) = (-*dx / norm, -*dy / norm, 1.0 / norm);
        }
    }
}

/// One channel of the ambient background, darkened by the internal shadow.
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn shade_channel(channel: &mut [f64], background: &[u8], c: usize, ka: f64, shadow: &[f64]) {
    for ((value, b), shadow) in channel
        .iter_mut()
        .zip(background[c..].iter().step_by(3))
        .zip(shadow)
    {
        *value = blend(ka * f64::from(*b), *shadow, 0.0);
    }
}

/// Blends one light into the three channels, given the unit normals (SIMD-multiversioned:
/// truncation is one instruction from SSE4.1 on).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn light_pass(normals: [&[f64]; 3], channels: [&mut [f64]; 3], light: &PhongLight) {
    // The reference's exponent is 5; a constant one lets the loop vectorise.
    if light.alpha == 5 {
        light_pass_with(normals, channels, light, |x| {
            let square = x * x;
            square * square * x
        });
    } else {
        let alpha = light.alpha;
        light_pass_with(normals, channels, light, |x| int_pow(x, alpha));
    }
}

#[inline(always)]
fn light_pass_with(
    [nx, ny, nz]: [&[f64]; 3],
    [red, green, blue]: [&mut [f64]; 3],
    light: &PhongLight,
    power: impl Fn(f64) -> f64,
) {
    let [lx, ly, lz] = light.position;
    let [cr, cg, cb] = light.colour;
    let (kd, ks) = (light.kd, light.ks);
    let normals = nx.iter().zip(ny).zip(nz);
    let channels = red.iter_mut().zip(green.iter_mut()).zip(blue.iter_mut());
    for (((x, y), z), ((r, g), b)) in normals.zip(channels) {
        let dot = x * lx + y * ly + z * lz;
        let intensity = (kd * dot).max(0.0) + ks * power(2.0 * dot * z - lz);
        *r = blend(*r, intensity, cr);
        *g = blend(*g, intensity, cg);
        *b = blend(*b, intensity, cb);
    }
}

/// Rounds (half to even) and saturates three channels into interleaved RGB, as OpenCV stores a
/// filtered u8 image.
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn store_pixels([red, green, blue]: [&[f64]; 3], out: &mut [u8]) {
    let byte = |value: f64| value.round_ties_even().clamp(0.0, 255.0) as u8;
    for (((pixel, r), g), b) in out.chunks_exact_mut(3).zip(red).zip(green).zip(blue) {
        pixel.copy_from_slice(&[byte(*r), byte(*g), byte(*b)]);
    }
}

/// The reference's overlay: `clip((1 − α)·value + α·colour, 0, 255)` truncated to an integer
/// (it casts to u8 after every blend).
#[inline(always)]
fn blend(value: f64, alpha: f64, colour: f64) -> f64 {
    ((1.0 - alpha) * value + alpha * colour)
        .clamp(0.0, 255.0)
        .trunc()
}
