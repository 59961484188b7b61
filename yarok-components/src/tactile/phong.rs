//! The Phong model of DIGIT and GelSight sensors: a depth map of the elastomer's inside, in,
//! a sensor image, out (the published simulation of Gomes et al. and its DIGIT port).

use multiversion::multiversion;

use super::field::{BlurScratch, Field};
use super::filter::gaussian_kernel;
use super::rows::{RowRing, in_bands_with, join, neighbours};
use super::{SizeError, expect_len, image_height, int_pow};

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
///
/// ```
/// use yarok_components::tactile::default_background;
/// use yarok_components::tactile::phong::{PhongModel, PhongParams};
///
/// // A DIGIT frame (240 columns × 320 rows) in metres: the gel's surface 30 mm from the camera,
/// // a flat-ended pin pressed 0.5 mm into it in the middle.
/// let (width, height) = (240, 320);
/// let depth: Vec<f32> = (0..width * height)
///     .map(|i| {
///         let (x, y) = ((i % width) as f32 - 120.0, (i / width) as f32 - 160.0);
///         if x * x + y * y < 400.0 { 0.0295 } else { 0.030 }
///     })
///     .collect();
/// let background = default_background(width, height);
/// let mut digit = PhongModel::new(PhongParams::digit_metric());
/// let pressed = digit.render(&depth, width, &background)?;
/// let untouched = digit.render(&vec![0.030; width * height], width, &background)?;
/// assert_eq!(pressed.len(), height * width * 3); // RGB, top row first
/// assert_ne!(pressed, untouched);
/// assert!(digit.render(&depth, 250, &background).is_err()); // not whole rows of 250
/// # Ok::<(), yarok_components::tactile::SizeError>(())
/// ```
///
/// A model is `Send`: several sensors render side by side on threads of their own, and
/// `set_parallel` (feature `parallel`) splits one frame's work when a single large image is the
/// bottleneck.
#[derive(Debug, Clone)]
pub struct PhongModel {
    params: PhongParams,
    narrow_kernel: Vec<f32>,
    wide_kernel: Vec<f32>,
    blur: [f64; 3],
    parallel: bool,
    scratch: Scratch,
}

/// Buffers of one image size.
#[derive(Debug, Clone)]
struct Scratch {
    indentation: Field,
    narrow: Smoothing,
    wide: Smoothing,
    noise: Vec<f64>,
    bands: Vec<RowBuffers>,
}

impl PhongModel {
    /// A model with these parameters.
    pub fn new(params: PhongParams) -> Self {
        let single = |kernel: Vec<f64>| kernel.into_iter().map(|k| k as f32).collect();
        let blur = gaussian_kernel(3, 1.0);
        Self {
            params,
            narrow_kernel: single(gaussian_kernel(21, 7.0)),
            wide_kernel: single(gaussian_kernel(52, 9.0)),
            blur: [blur[0], blur[1], blur[2]],
            parallel: false,
            scratch: Scratch {
                indentation: Field::empty(),
                narrow: Smoothing::new(),
                wide: Smoothing::new(),
                noise: Vec::new(),
                bands: Vec::new(),
            },
        }
    }

    /// Splits each frame's work into bands of rows on rayon's thread pool (`true`) or runs it on
    /// the calling thread (`false`, the default). The images are the same byte for byte.
    ///
    /// ```
    /// use yarok_components::tactile::phong::{PhongModel, PhongParams};
    ///
    /// let mut model = PhongModel::new(PhongParams::digit());
    /// model.set_parallel(true);
    /// ```
    #[cfg(feature = "parallel")]
    pub fn set_parallel(&mut self, parallel: bool) {
        self.parallel = parallel;
    }

    /// Renders the sensor image for `depth` (`height × width`, row-major, in the parameters'
    /// unit) over `background` (RGB, `height × width × 3`). Returns RGB, `height × width × 3`.
    ///
    /// # Errors
    ///
    /// [`SizeError`] when `depth` is not whole rows of `width` or `background` is not its size.
    pub fn render(
        &mut self,
        depth: &[f32],
        width: usize,
        background: &[u8],
    ) -> Result<Vec<u8>, SizeError> {
        let mut out = vec![0; background.len()];
        self.render_into(depth, width, background, &mut out)?;
        Ok(out)
    }

    /// [`PhongModel::render`] into a caller's buffer (`height × width × 3`).
    ///
    /// # Errors
    ///
    /// [`SizeError`] when the sizes do not match; nothing is written then.
    pub fn render_into(
        &mut self,
        depth: &[f32],
        width: usize,
        background: &[u8],
        out: &mut [u8],
    ) -> Result<(), SizeError> {
        let height = image_height(depth.len(), width)?;
        expect_len("background", background.len(), 3, (width, height))?;
        expect_len("output", out.len(), 3, (width, height))?;
        let max_depth = self.params.max_depth();
        self.scratch.indentation.assign(
            width,
            depth
                .iter()
                .map(|&d| (max_depth - f64::from(d).min(max_depth)) as f32),
        );
        self.deform();
        let s = &mut self.scratch;
        let frame = Frame {
            width,
            height,
            depth,
            background,
            narrow: &s.narrow.field.values,
            wide: &s.wide.field.values,
            noise: &s.noise,
        };
        let shading = Shading::new(&self.params, self.blur);
        in_bands_with(
            0..frame.height,
            3 * width,
            out,
            &mut s.bands,
            self.parallel,
            |rows, buffers, out| shade_rows(&shading, &frame, rows, buffers, out),
        );
        Ok(())
    }

    /// Elastic deformation: the indentation smoothed by two Gaussians (difference of Gaussians),
    /// each iteration renormalised to keep the indentation's peak. Runs in f32 like the reference,
    /// on the part of the image a press changes. Leaves the two smoothed fields in `narrow` and
    /// `wide` (computed side by side when parallel), and the texture noise for this image size in
    /// `noise`.
    fn deform(&mut self) {
        let s = &mut self.scratch;
        let p = &self.params;
        let peak = s.indentation.max();
        let narrow = [(&self.narrow_kernel[..], p.iterations)];
        let wide = [
            (&self.wide_kernel[..], p.iterations),
            (&self.narrow_kernel[..], p.iterations),
        ];
        let wide = if p.extra_passes {
            &wide[..]
        } else {
            &wide[..1]
        };
        let indentation = &s.indentation;
        // The two chains are independent: on two threads when parallel, a coarser split than
        // bands of rows for these short passes.
        join(
            self.parallel,
            || s.narrow.smooth(indentation, peak, &narrow, self.parallel),
            || s.wide.smooth(indentation, peak, wide, self.parallel),
        );
        let pixels = indentation.values.len();
        if p.texture_sigma <= 0.0 {
            s.noise.clear();
        } else if s.noise.len() != pixels {
            s.noise = super::noise::SplitMix64::new(p.seed).normal(pixels, p.texture_sigma);
        }
    }
}

/// One chain of the elastic deformation: the indentation smoothed again and again, each time
/// renormalised to the indentation's peak and kept at least as deep as it.
#[derive(Debug, Clone)]
struct Smoothing {
    field: Field,
    blurred: Field,
    blur: BlurScratch,
}

impl Smoothing {
    fn new() -> Self {
        Self {
            field: Field::empty(),
            blurred: Field::empty(),
            blur: BlurScratch::default(),
        }
    }

    /// Smooths `indentation` (whose maximum is `peak`) with each kernel the given number of
    /// times, in order; the result is in `self.field`.
    fn smooth(
        &mut self,
        indentation: &Field,
        peak: f32,
        kernels: &[(&[f32], usize)],
        parallel: bool,
    ) {
        self.field.copy_from(indentation);
        for &(kernel, times) in kernels {
            for _ in 0..times {
                self.field
                    .blur_into(kernel, &mut self.blur, &mut self.blurred, parallel);
                let peak_out = self.blurred.max();
                let ratio = if peak_out <= 0.0 {
                    1.0
                } else {
                    peak / peak_out
                };
                self.blurred.scale_at_least(ratio, indentation, parallel);
                std::mem::swap(&mut self.field, &mut self.blurred);
            }
        }
    }
}

/// What one frame's shading reads: the input, the two deformation fields and the texture noise
/// (empty for none).
struct Frame<'a> {
    width: usize,
    height: usize,
    depth: &'a [f32],
    background: &'a [u8],
    narrow: &'a [f32],
    wide: &'a [f32],
    noise: &'a [f64],
}

/// The parameters of the shading stage, in the form its loops use.
struct Shading<'a> {
    lights: &'a [PhongLight],
    ka: f64,
    max_depth: f64,
    thickness: f64,
    px2m_ratio: f64,
    blur: [f64; 3],
}

impl<'a> Shading<'a> {
    fn new(params: &'a PhongParams, blur: [f64; 3]) -> Self {
        Self {
            lights: &params.lights,
            ka: params.ka,
            max_depth: params.max_depth(),
            thickness: params.elastomer_thickness,
            px2m_ratio: params.px2m_ratio,
            blur,
        }
    }
}

/// Row buffers of the shading stage: rows of the height map and lit (pre-blur) rows, each
/// computed once while the stage walks down the image.
#[derive(Debug, Clone, Default)]
struct RowBuffers {
    heights: RowRing<Vec<f64>>,
    lit: RowRing<[Vec<f64>; 3]>,
    normals: [Vec<f64>; 3],
    column_blurred: Vec<f64>,
    blurred: [Vec<f64>; 3],
}

impl RowBuffers {
    fn prepare(&mut self, width: usize) {
        self.heights.reset(|row| row.resize(width, 0.0));
        self.lit
            .reset(|channels| channels.iter_mut().for_each(|c| c.resize(width, 0.0)));
        for row in self.normals.iter_mut().chain(&mut self.blurred) {
            row.resize(width, 0.0);
        }
        self.column_blurred.resize(width, 0.0);
    }
}

/// Shades output rows `rows` of the frame into `out` (those rows, RGB interleaved): the height
/// map and its normals, the internal shadow, each light, and the final 3×3 blur, row by row so
/// that every buffer stays in cache (SIMD-multiversioned; the helpers inline into it).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn shade_rows<'a>(
    shading: &Shading<'a>,
    frame: &Frame<'a>,
    rows: std::ops::Range<usize>,
    buffers: &mut RowBuffers,
    out: &mut [u8],
) {
    let width = frame.width;
    buffers.prepare(width);
    let [a, b, c] = shading.blur;
    for (y, out_row) in rows.zip(out.chunks_exact_mut(3 * width)) {
        let rows = neighbours(y, frame.height);
        for row in rows {
            lit_row(shading, frame, row, buffers);
        }
        let [lit_above, lit, lit_below] = rows.map(|row| buffers.lit.get(row));
        for channel in 0..3 {
            let column = &mut buffers.column_blurred;
            let rows = lit_above[channel].iter().zip(&lit[channel]);
            for ((value, (up, centre)), down) in
                column.iter_mut().zip(rows).zip(&lit_below[channel])
            {
                *value = a * up + b * centre + c * down;
            }
            blur_row(column, [a, b, c], &mut buffers.blurred[channel]);
        }
        let [red, green, blue] = &buffers.blurred;
        store_row([red, green, blue], out_row);
    }
}

/// Makes `buffers.lit` hold the lit (pre-blur) channels of `row`.
#[inline(always)]
fn lit_row(shading: &Shading<'_>, frame: &Frame<'_>, row: usize, buffers: &mut RowBuffers) {
    let RowBuffers {
        heights,
        lit,
        normals,
        ..
    } = buffers;
    let Some(channels) = lit.claim(row) else {
        return;
    };
    let rows = neighbours(row, frame.height);
    for r in rows {
        if let Some(slot) = heights.claim(r) {
            height_row(shading, frame, r, slot);
        }
    }
    normals_row(rows.map(|r| heights.get(r).as_slice()), normals);
    let width = frame.width;
    let depth = &frame.depth[row * width..(row + 1) * width];
    let background = &frame.background[3 * row * width..3 * (row + 1) * width];
    for (c, channel) in channels.iter_mut().enumerate() {
        shadowed_ambient(shading, depth, background, c, channel);
    }
    let [red, green, blue] = channels;
    let [nx, ny, nz] = &*normals;
    for light in shading.lights {
        light_row([nx, ny, nz], [red, green, blue], light);
    }
}

/// Row `row` of the height map: the elastomer's depth (minus the deformation) plus texture, in
/// pixels.
#[inline(always)]
fn height_row(shading: &Shading<'_>, frame: &Frame<'_>, row: usize, heights: &mut [f64]) {
    let range = row * frame.width..(row + 1) * frame.width;
    let max_depth = shading.max_depth as f32;
    let scale = shading.px2m_ratio;
    let deformed = frame.narrow[range.clone()]
        .iter()
        .zip(&frame.wide[range.clone()]);
    let elastomer = deformed.map(|(a, b)| f64::from(max_depth - (2.0 * a - b)));
    if frame.noise.is_empty() {
        for (height, depth) in heights.iter_mut().zip(elastomer) {
            *height = depth / scale;
        }
    } else {
        for ((height, depth), noise) in heights.iter_mut().zip(elastomer).zip(&frame.noise[range]) {
            *height = (depth + noise) / scale;
        }
    }
}

/// Unit normals `(−∂x, −∂y, 1)/‖·‖` of the centre row of three height-map rows, with central
/// differences and OpenCV's reflect-101 border (so the derivative across an edge is zero).
#[inline(always)]
fn normals_row([above, row, below]: [&[f64]; 3], [nx, ny, nz]: &mut [Vec<f64>; 3]) {
    let width = row.len();
    nx[0] = 0.0;
    nx[width - 1] = 0.0;
    if width > 2 {
        let interior = nx[1..width - 1]
            .iter_mut()
            .zip(row[2..].iter().zip(&row[..width - 2]));
        for (dx, (right, left)) in interior {
            *dx = (right - left) / 2.0;
        }
    }
    let slopes = nx.iter_mut().zip(ny.iter_mut()).zip(nz.iter_mut());
    for (((dx, dy), dz), (a, b)) in slopes.zip(above.iter().zip(below)) {
        *dy = (b - a) / 2.0;
        let norm = (*dx * *dx + *dy * *dy + 1.0).sqrt();
        (*dx, *dy, *dz) = (-*dx / norm, -*dy / norm, 1.0 / norm);
    }
}

/// One channel of a row of the ambient background, darkened by the internal shadow.
#[inline(always)]
fn shadowed_ambient(
    shading: &Shading<'_>,
    depth: &[f32],
    background: &[u8],
    c: usize,
    channel: &mut [f64],
) {
    let (max_depth, thickness, ka) = (shading.max_depth, shading.thickness, shading.ka);
    let pixels = channel
        .iter_mut()
        .zip(background[c..].iter().step_by(3))
        .zip(depth);
    for ((value, b), d) in pixels {
        let shadow = ((max_depth - f64::from(*d).min(max_depth)) / thickness).clamp(0.0, 1.0);
        *value = blend(ka * f64::from(*b), shadow, 0.0);
    }
}

/// Blends one light into a row's three channels, given its unit normals.
#[inline(always)]
fn light_row(normals: [&[f64]; 3], channels: [&mut Vec<f64>; 3], light: &PhongLight) {
    // The reference's exponent is 5; a constant one lets the loop vectorise.
    if light.alpha == 5 {
        light_row_with(normals, channels, light, |x| {
            let square = x * x;
            square * square * x
        });
    } else {
        let alpha = light.alpha;
        light_row_with(normals, channels, light, |x| int_pow(x, alpha));
    }
}

#[inline(always)]
fn light_row_with(
    [nx, ny, nz]: [&[f64]; 3],
    [red, green, blue]: [&mut Vec<f64>; 3],
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

/// The row part of the final blur, `[a, b, c]` across `row` with reflect-101 ends.
#[inline(always)]
fn blur_row(row: &[f64], [a, b, c]: [f64; 3], out: &mut [f64]) {
    let width = row.len();
    if width < 2 {
        out.copy_from_slice(row);
        return;
    }
    out[0] = a * row[1] + b * row[0] + c * row[1];
    out[width - 1] = a * row[width - 2] + b * row[width - 1] + c * row[width - 2];
    let taps = row.iter().zip(&row[1..]).zip(&row[2..]);
    for (value, ((left, centre), right)) in out[1..width - 1].iter_mut().zip(taps) {
        *value = a * left + b * centre + c * right;
    }
}

/// Rounds (half to even) and saturates three channel rows into interleaved RGB, as OpenCV stores
/// a filtered u8 image.
#[inline(always)]
fn store_row([red, green, blue]: [&[f64]; 3], out: &mut [u8]) {
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
