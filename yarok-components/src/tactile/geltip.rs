//! The GelTip model: a finger-shaped sensor whose lights reach the membrane along per-pixel
//! "light fields" (Gomes et al.).

use std::path::Path;

use multiversion::multiversion;

use super::field::Field;
use super::filter::{correlate_columns, correlate_rows, gaussian_kernel};
use super::int_pow;
use super::npy::{self, NpyError};

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
        }
    }
}

/// The GelTip model for one sensor geometry: its undeformed membrane depth and light fields.
/// Buffers are reused from frame to frame.
#[derive(Debug, Clone)]
pub struct GelTipModel {
    params: GelTipParams,
    width: usize,
    background_depth: Vec<f32>,
    /// Per light, the direction *towards* the light at each pixel (the negated field).
    towards_lights: Vec<Vec<[f64; 3]>>,
    kernel: Vec<f32>,
    protrusion: Field,
    blurred: Field,
    rows: Vec<f32>,
    padded: Vec<f32>,
    points: Vec<[f64; 3]>,
    coordinate: Vec<f64>,
    derivative: Vec<f64>,
    tangents: [Vec<[f64; 3]>; 2],
}

impl GelTipModel {
    /// A model for membranes whose undeformed depth is `background_depth` (metres, row-major,
    /// `width` wide) with one light field (unit vectors from the light, per pixel) per light.
    ///
    /// # Panics
    ///
    /// When the numbers of lights and fields differ or their sizes do not match the depth.
    pub fn new(
        params: GelTipParams,
        background_depth: &[f32],
        width: usize,
        light_fields: &[Vec<[f32; 3]>],
    ) -> Self {
        assert_eq!(
            params.lights.len(),
            light_fields.len(),
            "one light field per light"
        );
        assert!(
            light_fields
                .iter()
                .all(|f| f.len() == background_depth.len()),
            "light fields must match the depth's size"
        );
        let towards_lights = light_fields
            .iter()
            .map(|field| {
                field
                    .iter()
                    .map(|v| [-f64::from(v[0]), -f64::from(v[1]), -f64::from(v[2])])
                    .collect()
            })
            .collect();
        Self {
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
            rows: Vec::new(),
            padded: Vec::new(),
            points: Vec::new(),
            coordinate: Vec::new(),
            derivative: Vec::new(),
            tangents: [Vec::new(), Vec::new()],
        }
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
        let background = npy::read(dir.join("bkg_depth_m.npy.gz"))?;
        let [height, width] = background.shape[..] else {
            let message = format!("expected a 2-D depth map, got shape {:?}", background.shape);
            return Err(NpyError::Format {
                path: dir.join("bkg_depth_m.npy.gz").display().to_string(),
                message,
            });
        };
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
        Ok(Self::new(params, &background.data, width, &fields))
    }

    /// The size of the images the model renders: `(width, height)`.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.background_depth.len() / self.width)
    }

    /// Renders the sensor image for `depth` (metres; the membrane where nothing presses, less
    /// where something does) over `background` (RGB u8). Returns RGB, same size.
    ///
    /// # Panics
    ///
    /// When sizes do not match the model's.
    pub fn render(&mut self, depth: &[f32], background: &[u8]) -> Vec<u8> {
        let mut out = vec![0; background.len()];
        self.render_into(depth, background, &mut out);
        out
    }

    /// [`GelTipModel::render`] into a caller's buffer.
    ///
    /// # Panics
    ///
    /// When sizes do not match the model's.
    pub fn render_into(&mut self, depth: &[f32], background: &[u8], out: &mut [u8]) {
        assert_eq!(
            depth.len(),
            self.background_depth.len(),
            "depth size differs from the model's"
        );
        assert_eq!(
            background.len(),
            3 * depth.len(),
            "background must be width × height × 3"
        );
        assert_eq!(
            out.len(),
            background.len(),
            "output must be width × height × 3"
        );
        self.deform_and_back_project(depth);
        self.tangents();
        shade(
            &self.params,
            &self.points,
            &self.tangents,
            &self.towards_lights,
            background,
            out,
        );
    }

    /// `depth = min(depth, bkg − blur(bkg − depth))` in f32 like the reference, on the part of
    /// the image a press changes; then pixels to camera-frame points (`z` = depth / 1000, as the
    /// reference's Open3D call).
    fn deform_and_back_project(&mut self, depth: &[f32]) {
        let width = self.width;
        self.protrusion.assign(
            width,
            depth.iter().zip(&self.background_depth).map(|(d, b)| b - d),
        );
        self.protrusion.blur_into(
            &self.kernel,
            &mut self.rows,
            &mut self.padded,
            &mut self.blurred,
        );
        let (f, cx, cy) = pinhole(width, depth.len() / width, self.params.fov_deg);
        self.points.clear();
        self.points.extend(
            depth
                .iter()
                .zip(&self.background_depth)
                .zip(&self.blurred.values)
                .enumerate()
                .map(|(i, ((d, b), e))| {
                    let z = f64::from(d.min(b - e)) / 1000.0;
                    let (u, v) = ((i % width) as f64, (i / width) as f64);
                    [(u - cx) * z / f, (v - cy) * z / f, z]
                }),
        );
    }

    fn tangents(&mut self) {
        tangents_into(
            &self.points,
            self.width,
            &mut self.coordinate,
            &mut self.derivative,
            &mut self.tangents,
        );
    }
}

/// The Phong-like shading of every pixel from its point, tangents and the light fields
/// (SIMD-multiversioned; the reference's exponent 100 is unrolled).
#[multiversion(targets("x86_64+avx512f+avx512vl", "x86_64+avx2"))]
fn shade(
    params: &GelTipParams,
    points: &[[f64; 3]],
    tangents: &[Vec<[f64; 3]>; 2],
    towards_lights: &[Vec<[f64; 3]>],
    background: &[u8],
    out: &mut [u8],
) {
    for (pixel, point) in points.iter().enumerate() {
        let normal = surface_normal(tangents[0][pixel], tangents[1][pixel]);
        let view = scale(normalised(*point), -1.0);
        let mut light_sum = [0.0; 3];
        for (light, towards) in params.lights.iter().zip(towards_lights) {
            let l = towards[pixel];
            let ln = dot(l, normal);
            let reflected = [
                2.0 * ln * normal[0] - l[0],
                2.0 * ln * normal[1] - l[1],
                2.0 * ln * normal[2] - l[2],
            ];
            let diffuse = if params.clamp_diffuse {
                ln.max(0.0)
            } else {
                ln
            };
            let alignment = dot(reflected, view);
            let specular = if light.alpha == 100 {
                pow100(alignment)
            } else {
                int_pow(alignment, light.alpha)
            };
            let weight = light.id * diffuse + light.is * specular;
            for (sum, colour) in light_sum.iter_mut().zip(light.colour) {
                *sum += weight * colour / 255.0;
            }
        }
        for c in 0..3 {
            let intensity = params.ia * f64::from(background[3 * pixel + c]) / 255.0 + light_sum[c];
            out[3 * pixel + c] = (intensity * 255.0).clamp(0.0, 255.0) as u8;
        }
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

/// Focal length and centre, in pixels, of a camera `height` pixels high with vertical field of
/// view `fov_deg` (square pixels; the centre between the middle pixels).
pub(crate) fn pinhole(width: usize, height: usize, fov_deg: f64) -> (f64, f64, f64) {
    let f = height as f64 / (2.0 * (fov_deg.to_radians() / 2.0).tan());
    (f, (width as f64 - 1.0) / 2.0, (height as f64 - 1.0) / 2.0)
}

/// Central differences of a grid of points along rows (`tangents[0]`) and columns
/// (`tangents[1]`), with reflect-101 borders; `coordinate` and `derivative` are scratch.
pub(crate) fn tangents_into(
    points: &[[f64; 3]],
    width: usize,
    coordinate: &mut Vec<f64>,
    derivative: &mut Vec<f64>,
    tangents: &mut [Vec<[f64; 3]>; 2],
) {
    let n = points.len();
    coordinate.resize(n, 0.0);
    derivative.resize(n, 0.0);
    for tangent in tangents.iter_mut() {
        tangent.resize(n, [0.0; 3]);
    }
    for c in 0..3 {
        for (value, point) in coordinate.iter_mut().zip(points) {
            *value = point[c];
        }
        correlate_rows(coordinate, width, &[-0.5, 0.0, 0.5], derivative);
        for (t, d) in tangents[0].iter_mut().zip(derivative.iter()) {
            t[c] = *d;
        }
        correlate_columns(coordinate, width, &[-0.5, 0.0, 0.5], derivative);
        for (t, d) in tangents[1].iter_mut().zip(derivative.iter()) {
            t[c] = *d;
        }
    }
}

/// The surface normal from a pair of tangents, `−(t̂x × t̂y)` as the reference computes it.
pub(crate) fn surface_normal(tx: [f64; 3], ty: [f64; 3]) -> [f64; 3] {
    let (a, b) = (normalised(tx), normalised(ty));
    [
        -(a[1] * b[2] - a[2] * b[1]),
        -(a[2] * b[0] - a[0] * b[2]),
        -(a[0] * b[1] - a[1] * b[0]),
    ]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// The unit vector along `a`; vectors shorter than 1e-9 are left as they are, as in the reference.
pub(crate) fn normalised(a: [f64; 3]) -> [f64; 3] {
    let norm = dot(a, a).sqrt();
    if norm < 1e-9 { a } else { scale(a, 1.0 / norm) }
}
