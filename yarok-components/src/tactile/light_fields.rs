//! GelTip light fields computed from the sensor's geometry, so that users are not tied to
//! precomputed files: for each pixel, the unit direction in which an LED's light travels when it
//! reaches the membrane point that pixel sees.

use super::geltip::{Camera, back_project_row, dot, normalised, normals_row};
use super::rows::{RowRing, neighbours};

/// How light is taken to travel from an LED to a membrane point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum LightFieldMethod {
    /// In a straight line from the LED (the reference's "linear" fields).
    Linear,
    /// Within the membrane, along the curve where the plane through the LED, the point and the
    /// sensor's axis cuts it (the reference's "plane" fields): the direction is tangent to the
    /// membrane.
    Plane,
}

/// The light field of an LED at `led` (camera frame, metres; the camera looks along +z) for a
/// membrane whose depth, as the sensor's camera sees it, is `membrane_depth` (metres, row-major,
/// `width` wide, vertical field of view `fov_deg`). One unit vector per pixel, pointing away from
/// the light, as [`GelTipModel::new`](super::geltip::GelTipModel::new) takes them.
pub fn light_field(
    membrane_depth: &[f32],
    width: usize,
    fov_deg: f64,
    led: [f64; 3],
    method: LightFieldMethod,
) -> Vec<[f32; 3]> {
    let height = membrane_depth.len() / width;
    let camera = Camera::new(width, height, fov_deg);
    let mut points = RowRing::<[Vec<f64>; 3]>::default();
    points.reset(|row| row.iter_mut().for_each(|c| c.resize(width, 0.0)));
    let (mut tangent, mut normal) = (
        [0; 3].map(|_| vec![0.0; width]),
        [0; 3].map(|_| vec![0.0; width]),
    );
    let mut field = Vec::with_capacity(membrane_depth.len());
    for y in 0..height {
        let rows = neighbours(y, height);
        for row in rows {
            let depth = &membrane_depth[row * width..(row + 1) * width];
            if let Some(points) = points.claim(row) {
                back_project_row(camera, row, depth, 1.0, points);
            }
        }
        normals_row(rows.map(|row| points.get(row)), &mut tangent, &mut normal);
        let row = points.get(y);
        for x in 0..width {
            let point = [row[0][x], row[1][x], row[2][x]];
            let away = [point[0] - led[0], point[1] - led[1], point[2] - led[2]];
            let direction = match method {
                LightFieldMethod::Linear => normalised(away),
                LightFieldMethod::Plane => {
                    along_membrane(away, [normal[0][x], normal[1][x], normal[2][x]])
                }
            };
            field.push(direction.map(|v| v as f32));
        }
    }
    field
}

/// The tangent of the membrane's cut by the plane holding `away` and the sensor axis (+z),
/// oriented away from the light; `away` itself where that plane is undefined.
fn along_membrane(away: [f64; 3], surface: [f64; 3]) -> [f64; 3] {
    let axis = [0.0, 0.0, 1.0];
    let plane = normalised(cross(away, axis));
    let tangent = cross(plane, surface);
    let length = dot(tangent, tangent).sqrt();
    if dot(plane, plane) < 0.5 || length < 1e-9 {
        return normalised(away);
    }
    let sign = if dot(tangent, away) < 0.0 { -1.0 } else { 1.0 };
    tangent.map(|v| sign * v / length)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hemispherical membrane of radius 12 mm centred 30 mm in front of the camera.
    fn dome(width: usize, height: usize) -> Vec<f32> {
        let camera = Camera::new(width, height, 70.0);
        (0..width * height)
            .map(|i| {
                let ray = normalised(camera.point((i % width) as f64, (i / width) as f64, 1.0));
                // Nearest intersection of the ray with the sphere |p − c| = r, c = (0, 0, 0.030).
                let (c, r) = (0.030, 0.012);
                let b = ray[2] * c;
                let disc = b * b - (c * c - r * r);
                let t = if disc >= 0.0 {
                    b - disc.sqrt()
                } else {
                    c / ray[2]
                };
                (t * ray[2]) as f32
            })
            .collect()
    }

    #[test]
    fn fields_are_unit_vectors_pointing_away_from_the_led() {
        let (width, height) = (64, 48);
        let depth = dome(width, height);
        let led = [0.012, 0.0, 0.030];
        let camera = Camera::new(width, height, 70.0);
        for method in [LightFieldMethod::Linear, LightFieldMethod::Plane] {
            let field = light_field(&depth, width, 70.0, led, method);
            for (i, v) in field.iter().enumerate() {
                let v = v.map(f64::from);
                assert!((dot(v, v) - 1.0).abs() < 1e-5, "{method:?} pixel {i}");
                let z = f64::from(depth[i]);
                let point = camera.point((i % width) as f64, (i / width) as f64, z);
                let away = [point[0] - led[0], point[1] - led[1], point[2] - led[2]];
                assert!(
                    dot(v, away) >= -1e-9,
                    "{method:?} pixel {i} points towards the LED"
                );
            }
        }
    }

    #[test]
    fn plane_fields_run_along_the_membrane() {
        let (width, height) = (64, 48);
        let depth = dome(width, height);
        let field = light_field(
            &depth,
            width,
            70.0,
            [0.012, 0.0, 0.030],
            LightFieldMethod::Plane,
        );
        let linear = light_field(
            &depth,
            width,
            70.0,
            [0.012, 0.0, 0.030],
            LightFieldMethod::Linear,
        );
        // At the dome's tip (centre pixel) the surface faces the camera: the plane field is
        // horizontal, while the straight line from the LED dips towards the camera.
        let centre = (height / 2) * width + width / 2;
        assert!(field[centre][2].abs() < 0.05, "{:?}", field[centre]);
        assert!(linear[centre][2] < -0.5, "{:?}", linear[centre]);
    }
}
