//! The GelTip model: a finger-shaped sensor whose lights reach the membrane along per-pixel
//! "light fields" (Gomes et al.).

use super::field::Field;
use super::filter::{correlate_columns, correlate_rows, gaussian_kernel};

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
#[derive(Debug, Clone)]
pub struct GelTipModel {
    params: GelTipParams,
    width: usize,
    background_depth: Vec<f64>,
    /// Per light, the direction *towards* the light at each pixel (the negated field).
    towards_lights: Vec<Vec<[f64; 3]>>,
    kernel: Vec<f32>,
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
            background_depth: background_depth.iter().map(|&d| f64::from(d)).collect(),
            towards_lights,
            kernel: gaussian_kernel(95, 9.0)
                .into_iter()
                .map(|k| k as f32)
                .collect(),
        }
    }

    /// Renders the sensor image for `depth` (metres; the membrane where nothing presses, less
    /// where something does) over `background` (RGB u8). Returns RGB, same size.
    ///
    /// # Panics
    ///
    /// When sizes do not match the model's.
    pub fn render(&self, depth: &[f32], background: &[u8]) -> Vec<u8> {
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
        let deformed = self.deform(depth);
        let points = self.back_project(&deformed);
        let normals = self.normals(&points);
        let mut out = Vec::with_capacity(background.len());
        for (pixel, (point, normal)) in points.iter().zip(&normals).enumerate() {
            let view = scale(normalised(*point), -1.0);
            let mut light_sum = [0.0; 3];
            for (light, towards) in self.params.lights.iter().zip(&self.towards_lights) {
                let l = towards[pixel];
                let ln = dot(l, *normal);
                let reflected = [
                    2.0 * ln * normal[0] - l[0],
                    2.0 * ln * normal[1] - l[1],
                    2.0 * ln * normal[2] - l[2],
                ];
                let diffuse = if self.params.clamp_diffuse {
                    ln.max(0.0)
                } else {
                    ln
                };
                let weight = light.id * diffuse + light.is * dot(reflected, view).powi(light.alpha);
                for (sum, colour) in light_sum.iter_mut().zip(light.colour) {
                    *sum += weight * colour / 255.0;
                }
            }
            for c in 0..3 {
                let intensity =
                    self.params.ia * f64::from(background[3 * pixel + c]) / 255.0 + light_sum[c];
                out.push((intensity * 255.0).clamp(0.0, 255.0) as u8);
            }
        }
        out
    }

    /// `depth = min(depth, bkg − blur(bkg − depth))`, in f32 like the reference, on the part
    /// of the image a press changes.
    fn deform(&self, depth: &[f32]) -> Vec<f64> {
        let protrusion: Vec<f32> = depth
            .iter()
            .zip(&self.background_depth)
            .map(|(d, b)| (*b as f32) - d)
            .collect();
        let blurred = Field::new(protrusion, self.width).blur(&self.kernel);
        depth
            .iter()
            .zip(&self.background_depth)
            .zip(&blurred.values)
            .map(|((d, b), e)| f64::from(d.min(*b as f32 - e)))
            .collect()
    }

    /// Pixels to camera-frame points (`z` = depth / 1000, as the reference's Open3D call).
    fn back_project(&self, depth: &[f64]) -> Vec<[f64; 3]> {
        let height = depth.len() / self.width;
        let f = height as f64 / (2.0 * (self.params.fov_deg.to_radians() / 2.0).tan());
        let (cx, cy) = ((self.width as f64 - 1.0) / 2.0, (height as f64 - 1.0) / 2.0);
        depth
            .iter()
            .enumerate()
            .map(|(i, d)| {
                let z = d / 1000.0;
                let (u, v) = ((i % self.width) as f64, (i / self.width) as f64);
                [(u - cx) * z / f, (v - cy) * z / f, z]
            })
            .collect()
    }

    /// `n = −(normalise(∂x S) × normalise(∂y S))` with central differences per coordinate.
    fn normals(&self, points: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let mut tangents = [vec![[0.0; 3]; points.len()], vec![[0.0; 3]; points.len()]];
        let mut channel = vec![0.0; points.len()];
        let mut derivative = vec![0.0; points.len()];
        for c in 0..3 {
            for (value, point) in channel.iter_mut().zip(points) {
                *value = point[c];
            }
            correlate_rows(&channel, self.width, &[-0.5, 0.0, 0.5], &mut derivative);
            for (t, d) in tangents[0].iter_mut().zip(&derivative) {
                t[c] = *d;
            }
            correlate_columns(&channel, self.width, &[-0.5, 0.0, 0.5], &mut derivative);
            for (t, d) in tangents[1].iter_mut().zip(&derivative) {
                t[c] = *d;
            }
        }
        tangents[0]
            .iter()
            .zip(&tangents[1])
            .map(|(tx, ty)| {
                let (a, b) = (normalised(*tx), normalised(*ty));
                [
                    -(a[1] * b[2] - a[2] * b[1]),
                    -(a[2] * b[0] - a[0] * b[2]),
                    -(a[0] * b[1] - a[1] * b[0]),
                ]
            })
            .collect()
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// The unit vector along `a`; vectors shorter than 1e-9 are left as they are, as in the reference.
fn normalised(a: [f64; 3]) -> [f64; 3] {
    let norm = dot(a, a).sqrt();
    if norm < 1e-9 { a } else { scale(a, 1.0 / norm) }
}
