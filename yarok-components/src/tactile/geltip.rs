//! The GelTip model: a finger-shaped sensor whose lights reach the membrane along per-pixel
//! "light fields" (Gomes et al.).

use std::path::Path;

use multiversion::multiversion;

use super::field::{BlurScratch, Field};
use super::filter::gaussian_kernel;
use super::light_fields::{LightFieldMethod, light_field};
use super::npy::{self, NpyError};
use super::rows::{RowRing, in_bands_with, neighbours};
use super::surface::{Camera, back_project_row, dot, normalised, normals_row, scale};
use super::{SizeError, expect_len, image_height, int_pow};

/// A light of the GelTip model.
#[derive(Debug, Clone, PartialEq)]
pub struct GelTipLight {
    /// Colour, RGB 0–255.
    pub colour: [f64; 3],
    /// Diffuse coefficient.
    pub id: f64,
    /// Specular coefficient.
    pub is: f64,
    /// Specular exponent.
    pub alpha: i32,
}

/// Parameters of the GelTip model; [`GelTipParams::default`] is the reference's.
#[derive(Debug, Clone, PartialEq)]
pub struct GelTipParams {
    /// Lights; each needs a light field of the image's size.
    pub lights: Vec<GelTipLight>,
    /// Ambient coefficient applied to the background.
    pub ia: f64,
    /// Vertical field of view of the sensor's camera, degrees.
    pub fov_deg: f64,
    /// Clamp negative diffuse terms to zero. The reference does not, which darkens surfaces facing
    /// away from a light below the ambient level (dark crescents around contacts); `false` keeps
    /// its output, `true` is the physically sensible correction.
    pub clamp_diffuse: bool,
    /// Pixels where nothing was measured (depth zero, negative or not finite) take the
    /// undeformed membrane's depth. The reference drops such pixels from its point cloud and then
    /// fails to shape it back into an image, so there is no output of its to keep; `false`
    /// back-projects them as given (to the camera's centre, with meaningless normals around).
    pub fill_missing_depth: bool,
}

impl Default for GelTipParams {
    fn default() -> Self {
        let light = |colour| GelTipLight {
            colour,
            id: 0.5,
            is: 0.1,
            alpha: 100,
        };
        Self {
            lights: vec![
                light([255.0, 94.0, 196.0]),
                light([255.0, 144.0, 154.0]),
                light([255.0, 175.0, 104.0]),
            ],
            ia: 0.8,
            fov_deg: 70.0,
            clamp_diffuse: false,
            fill_missing_depth: true,
        }
    }
}

/// The GelTip model for one sensor geometry: its undeformed membrane depth and light fields.
/// Buffers are reused from frame to frame.
///
/// ```
/// use yarok_components::tactile::geltip::{GelTipModel, GelTipParams};
/// use yarok_components::tactile::light_fields::{LightFieldMethod, led_ring};
///
/// // A (flat, for brevity) membrane 20 mm in front of a 64 × 48 camera, lit by three LEDs on a
/// // ring of 12 mm around the camera, with light fields computed from that geometry.
/// let (width, height) = (64, 48);
/// let membrane = vec![0.020f32; width * height];
/// let leds = led_ring(3, 0.012, 0.0);
/// let mut geltip = GelTipModel::from_geometry(
///     GelTipParams::default(),
///     &membrane,
///     width,
///     &leds,
///     LightFieldMethod::Linear,
/// )?;
/// let mut pressed = membrane.clone();
/// pressed[24 * width + 32] = 0.019; // a pin pushes the membrane 1 mm in
/// let background = vec![0u8; width * height * 3];
/// let image = geltip.render(&pressed, &background)?;
/// assert_eq!(image.len(), width * height * 3); // RGB, top row first
/// assert_ne!(image, geltip.render(&membrane, &background)?);
/// # Ok::<(), yarok_components::tactile::SizeError>(())
/// ```
#[derive(Debug, Clone)]
pub struct GelTipModel {
    params: GelTipParams,
    width: usize,
    background_depth: Vec<f32>,
    /// Per light, the direction *towards* the light at each pixel (the negated field), as three
    /// planes x, y, z.
    towards_lights: Vec<[Vec<f32>; 3]>,
    kernel: Vec<f32>,
    protrusion: Field,
    blurred: Field,
    blur: BlurScratch,
    surface: Vec<f32>,
    bands: Vec<RowBuffers>,
    parallel: bool,
}

impl GelTipModel {
    /// A model for membranes whose undeformed depth is `background_depth` (metres, row-major,
    /// `width` wide) with one light field (unit vectors from the light, per pixel) per light.
    ///
    /// # Errors
    ///
    /// [`SizeError`] when the depth is not whole rows, the numbers of lights and fields differ,
    /// or a field's size is not the depth's.
    pub fn new(
        params: GelTipParams,
        background_depth: &[f32],
        width: usize,
        light_fields: &[Vec<[f32; 3]>],
    ) -> Result<Self, SizeError> {
        let size = (width, image_height(background_depth.len(), width)?);
        if params.lights.len() != light_fields.len() {
            return Err(SizeError::LightCount {
                lights: params.lights.len(),
                fields: light_fields.len(),
            });
        }
        for field in light_fields {
            expect_len("light field", field.len(), 1, size)?;
        }
        let towards_lights = light_fields
            .iter()
            .map(|field| [0, 1, 2].map(|c| field.iter().map(|v| -v[c]).collect()))
            .collect();
        Ok(Self {
            params,
            width,
            background_depth: background_depth.to_vec(),
            towards_lights,
            kernel: gaussian_kernel(95, 9.0)
                .into_iter()
                .map(|k| k as f32)
                .collect(),
            protrusion: Field::empty(),
            blurred: Field::empty(),
            blur: BlurScratch::default(),
            surface: Vec::new(),
            bands: Vec::new(),
            parallel: false,
        })
    }

    /// Splits each frame's work into bands of rows on rayon's thread pool (`true`) or runs it on
    /// the calling thread (`false`, the default). The images are the same byte for byte.
    #[cfg(feature = "parallel")]
    pub fn set_parallel(&mut self, parallel: bool) {
        self.parallel = parallel;
    }

    /// A model whose light fields are computed from the membrane's geometry: its undeformed
    /// `membrane_depth` (metres, row-major, `width` wide) and one LED position per light (camera
    /// frame, metres), by `method`.
    ///
    /// # Errors
    ///
    /// [`SizeError`] when the depth is not whole rows or the numbers of lights and LEDs differ.
    pub fn from_geometry(
        params: GelTipParams,
        membrane_depth: &[f32],
        width: usize,
        leds: &[[f64; 3]],
        method: LightFieldMethod,
    ) -> Result<Self, SizeError> {
        if params.lights.len() != leds.len() {
            return Err(SizeError::LightCount {
                lights: params.lights.len(),
                fields: leds.len(),
            });
        }
        let fields = leds
            .iter()
            .map(|led| light_field(membrane_depth, width, params.fov_deg, *led, method))
            .collect::<Result<Vec<_>, _>>()?;
        Self::new(params, membrane_depth, width, &fields)
    }

    /// A model whose geometry is stored in `dir` as the reference stores it:
    /// `bkg_depth_m.npy.gz` (the undeformed membrane depth, metres, `height × width`) and
    /// `light_field_{i}.npy.gz` (`height × width × 3`), one per light.
    ///
    /// # Errors
    ///
    /// [`NpyError`] naming the file that is missing or has the wrong shape.
    pub fn load(params: GelTipParams, dir: impl AsRef<Path>) -> Result<Self, NpyError> {
        let dir = dir.as_ref();
        let (membrane, width) = read_membrane(dir)?;
        let height = membrane.len() / width;
        let fields = (0..params.lights.len())
            .map(|i| {
                let path = dir.join(format!("light_field_{i}.npy.gz"));
                let field = npy::read(&path)?;
                if field.shape != [height, width, 3] {
                    let message = format!(
                        "expected shape [{height}, {width}, 3], got {:?}",
                        field.shape
                    );
                    return Err(NpyError::Format {
                        path: path.display().to_string(),
                        message,
                    });
                }
                Ok(field
                    .data
                    .chunks_exact(3)
                    .map(|v| [v[0], v[1], v[2]])
                    .collect())
            })
            .collect::<Result<Vec<_>, NpyError>>()?;
        Self::new(params, &membrane, width, &fields).map_err(|e| NpyError::Format {
            path: dir.display().to_string(),
            message: e.to_string(),
        })
    }

    /// The size of the images the model renders: `(width, height)`.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.background_depth.len() / self.width)
    }

    /// Renders the sensor image for `depth` (metres; the membrane where nothing presses, less
    /// where something does) over `background` (RGB u8). Returns RGB, same size.
    ///
    /// # Errors
    ///
    /// [`SizeError`] when the sizes do not match the model's.
    pub fn render(&mut self, depth: &[f32], background: &[u8]) -> Result<Vec<u8>, SizeError> {
        let mut out = vec![0; background.len()];
        self.render_into(depth, background, &mut out)?;
        Ok(out)
    }

    /// [`GelTipModel::render`] into a caller's buffer.
    ///
    /// # Errors
    ///
    /// [`SizeError`] when the sizes do not match the model's; nothing is written then.
    pub fn render_into(
        &mut self,
        depth: &[f32],
        background: &[u8],
        out: &mut [u8],
    ) -> Result<(), SizeError> {
        let size = self.size();
        expect_len("depth map", depth.len(), 1, size)?;
        expect_len("background", background.len(), 3, size)?;
        expect_len("output", out.len(), 3, size)?;
        self.deform(depth);
        let (width, height) = self.size();
        let frame = Frame {
            camera: Camera::new(width, height, self.params.fov_deg),
            width,
            height,
            surface: &self.surface,
            towards_lights: &self.towards_lights,
            background,
        };
        let params = &self.params;
        in_bands_with(
            0..height,
            3 * width,
            out,
            &mut self.bands,
            self.parallel,
            |rows, buffers, out| shade_rows(params, &frame, rows, buffers, out),
        );
        Ok(())
    }

    /// `surface = min(depth, bkg − blur(bkg − depth))` in f32 like the reference, the blur on
    /// the part of the image a press changes; missing depths filled first if the parameters say
    /// so.
    fn deform(&mut self, depth: &[f32]) {
        let fill = self.params.fill_missing_depth;
        let measured = move |(d, b): (&f32, &f32)| {
            let missing = fill && !(*d > 0.0 && d.is_finite());
            (if missing { *b } else { *d }, *b)
        };
        self.protrusion.assign(
            self.width,
            depth
                .iter()
                .zip(&self.background_depth)
                .map(measured)
                .map(|(d, b)| b - d),
        );
        self.protrusion.blur_into(
            &self.kernel,
            &mut self.blur,
            &mut self.blurred,
            self.parallel,
        );
        self.surface.clear();
        self.surface.extend(
            depth
                .iter()
                .zip(&self.background_depth)
                .map(measured)
                .zip(&self.blurred.values)
                .map(|((d, b), e)| d.min(b - e)),
        );
    }
}

/// The undeformed membrane depth stored in `dir` as the reference stores it,
/// `bkg_depth_m.npy.gz` (metres, `height × width`), and its width.
///
/// # Errors
///
/// [`NpyError`] naming the file when it is missing or not a 2-D array.
pub fn read_membrane(dir: impl AsRef<Path>) -> Result<(Vec<f32>, usize), NpyError> {
    let path = dir.as_ref().join("bkg_depth_m.npy.gz");
    let membrane = npy::read(&path)?;
    match membrane.shape[..] {
        [height, width] if height > 0 && width > 0 => Ok((membrane.data, width)),
        _ => Err(NpyError::Format {
            path: path.display().to_string(),
            message: format!("expected a 2-D depth map, got shape {:?}", membrane.shape),
        }),
    }
}

/// The depth scale of the reference's back-projection (Open3D's, depth / 1000). It does not
/// change the unit vectors the model uses, only which tangents count as too short to normalise.
const BACK_PROJECTION_SCALE: f64 = 1e-3;

/// What one frame's shading reads.
struct Frame<'a> {
    camera: Camera,
    width: usize,
    height: usize,
    surface: &'a [f32],
    towards_lights: &'a [[Vec<f32>; 3]],
    background: &'a [u8],
}

/// Row buffers of the shading: back-projected rows, and the current row's normals, view
/// directions and light sums.
#[derive(Debug, Clone, Default)]
struct RowBuffers {
    points: RowRing<[Vec<f64>; 3]>,
    tangent: [Vec<f64>; 3],
    normal: [Vec<f64>; 3],
    view: [Vec<f64>; 3],
    light_sum: [Vec<f64>; 3],
}

impl RowBuffers {
    fn prepare(&mut self, width: usize) {
        self.points
            .reset(|row| row.iter_mut().for_each(|c| c.resize(width, 0.0)));
        let rows = [
            &mut self.tangent,
            &mut self.normal,
            &mut self.view,
            &mut self.light_sum,
        ];
        for row in rows.into_iter().flatten() {
            row.resize(width, 0.0);
        }
    }
}

/// Shades output rows `rows` into `out` (those rows, RGB interleaved): back-projection, normals
/// and the Phong-like lighting along the light fields, row by row (SIMD-multiversioned; the
/// reference's exponent 100 is unrolled).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn shade_rows<'a>(
    params: &GelTipParams,
    frame: &Frame<'a>,
    rows: std::ops::Range<usize>,
    buffers: &mut RowBuffers,
    out: &mut [u8],
) {
    let width = frame.width;
    buffers.prepare(width);
    for (y, out_row) in rows.zip(out.chunks_exact_mut(3 * width)) {
        let neighbours = neighbours(y, frame.height);
        for row in neighbours {
            let surface = &frame.surface[row * width..(row + 1) * width];
            if let Some(points) = buffers.points.claim(row) {
                back_project_row(frame.camera, row, surface, BACK_PROJECTION_SCALE, points);
            }
        }
        let [above, points, below] = neighbours.map(|row| buffers.points.get(row));
        normals_row(
            [above, points, below],
            &mut buffers.tangent,
            &mut buffers.normal,
        );
        view_row(points, &mut buffers.view);
        for sum in &mut buffers.light_sum {
            sum.fill(0.0);
        }
        for (light, towards) in params.lights.iter().zip(frame.towards_lights) {
            let towards = towards
                .each_ref()
                .map(|plane| &plane[y * width..(y + 1) * width]);
            light_row(params, light, towards, buffers);
        }
        let background = &frame.background[3 * y * width..3 * (y + 1) * width];
        store_row(params.ia, &buffers.light_sum, background, out_row);
    }
}

/// Adds one light's diffuse and specular terms, weighted by its colour, to the row's light sums.
#[inline(always)]
fn light_row(
    params: &GelTipParams,
    light: &GelTipLight,
    [lx, ly, lz]: [&[f32]; 3],
    buffers: &mut RowBuffers,
) {
    if light.alpha == 100 {
        light_row_with(params.clamp_diffuse, light, [lx, ly, lz], buffers, pow100);
    } else {
        let alpha = light.alpha;
        light_row_with(params.clamp_diffuse, light, [lx, ly, lz], buffers, |x| {
            int_pow(x, alpha)
        });
    }
}

#[inline(always)]
fn light_row_with(
    clamp_diffuse: bool,
    light: &GelTipLight,
    [lx, ly, lz]: [&[f32]; 3],
    buffers: &mut RowBuffers,
    power: impl Fn(f64) -> f64,
) {
    let [nx, ny, nz] = &buffers.normal;
    let [vx, vy, vz] = &buffers.view;
    let [red, green, blue] = &mut buffers.light_sum;
    let [cr, cg, cb] = light.colour.map(|c| c / 255.0);
    let normals = nx.iter().zip(ny).zip(nz);
    let views = vx.iter().zip(vy).zip(vz);
    let towards = lx.iter().zip(ly).zip(lz);
    let sums = red.iter_mut().zip(green.iter_mut()).zip(blue.iter_mut());
    for (((((nx, ny), nz), ((vx, vy), vz)), ((lx, ly), lz)), ((r, g), b)) in
        normals.zip(views).zip(towards).zip(sums)
    {
        let n = [*nx, *ny, *nz];
        let l = [f64::from(*lx), f64::from(*ly), f64::from(*lz)];
        let ln = dot(l, n);
        let reflected = [
            2.0 * ln * n[0] - l[0],
            2.0 * ln * n[1] - l[1],
            2.0 * ln * n[2] - l[2],
        ];
        let diffuse = if clamp_diffuse { ln.max(0.0) } else { ln };
        let alignment = dot(reflected, [*vx, *vy, *vz]);
        let weight = light.id * diffuse + light.is * power(alignment);
        *r += weight * cr;
        *g += weight * cg;
        *b += weight * cb;
    }
}

/// `ia · background + light sums`, saturated and truncated to bytes as the reference does.
#[inline(always)]
fn store_row(ia: f64, [red, green, blue]: &[Vec<f64>; 3], background: &[u8], out: &mut [u8]) {
    let sums = red.iter().zip(green).zip(blue);
    for ((pixel, base), ((r, g), b)) in out
        .chunks_exact_mut(3)
        .zip(background.chunks_exact(3))
        .zip(sums)
    {
        let byte = |base: u8, sum: f64| {
            ((ia * f64::from(base) / 255.0 + sum) * 255.0).clamp(0.0, 255.0) as u8
        };
        pixel.copy_from_slice(&[byte(base[0], *r), byte(base[1], *g), byte(base[2], *b)]);
    }
}

/// `x¹⁰⁰` by squaring: x⁶⁴ · x³² · x⁴.
#[inline(always)]
fn pow100(x: f64) -> f64 {
    let x2 = x * x;
    let x4 = x2 * x2;
    let x8 = x4 * x4;
    let x16 = x8 * x8;
    let x32 = x16 * x16;
    x32 * x32 * x32 * x4
}

/// Unit vectors from each point of a row towards the camera.
#[inline(always)]
fn view_row([px, py, pz]: &[Vec<f64>; 3], [vx, vy, vz]: &mut [Vec<f64>; 3]) {
    let points = px.iter().zip(py).zip(pz);
    for (((x, y), z), ((px, py), pz)) in vx
        .iter_mut()
        .zip(vy.iter_mut())
        .zip(vz.iter_mut())
        .zip(points)
    {
        [*x, *y, *z] = scale(normalised([*px, *py, *pz]), -1.0);
    }
}
