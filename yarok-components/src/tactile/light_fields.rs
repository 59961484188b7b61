//! GelTip light fields computed from the sensor's geometry, so that users are not tied to
//! precomputed files: for each pixel, the unit direction in which an LED's light travels when it
//! reaches the membrane point that pixel sees.

use super::rows::{RowRing, neighbours};
use super::surface::{Camera, back_project_row, dot, normalised, normals_row};
use super::{SizeError, image_height};

/// How light is taken to travel from an LED to a membrane point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum LightFieldMethod {
    /// In a straight line from the LED (the reference's "linear" fields).
    Linear,
    /// Within the membrane, along the curve where the upright plane (parallel to the sensor's
    /// axis) through the LED and the point cuts it (the reference's "plane" fields): the direction
    /// is tangent to the membrane, running on over the tip.
    Plane,
}

/// The light field of an LED at `led` (camera frame, metres; the camera looks along +z) for a
/// membrane whose depth, as the sensor's camera sees it, is `membrane_depth` (metres, row-major,
/// `width` wide, vertical field of view `fov_deg`). One unit vector per pixel, pointing away from
/// the light, as [`GelTipModel::new`](super::geltip::GelTipModel::new) takes them.
///
/// # Errors
///
/// [`SizeError`] when the depth is not whole rows of `width`.
pub fn light_field(
    membrane_depth: &[f32],
    width: usize,
    fov_deg: f64,
    led: [f64; 3],
    method: LightFieldMethod,
) -> Result<Vec<[f32; 3]>, SizeError> {
    let height = image_height(membrane_depth.len(), width)?;
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
            let direction = match method {
                LightFieldMethod::Linear => {
                    normalised([point[0] - led[0], point[1] - led[1], point[2] - led[2]])
                }
                LightFieldMethod::Plane => {
                    along_membrane(point, led, [normal[0][x], normal[1][x], normal[2][x]])
                }
            };
            field.push(direction.map(|v| v as f32));
        }
    }
    Ok(field)
}

/// `count` LEDs evenly spaced on a circle of `radius` (metres) around the camera's axis, `z`
/// (metres) in front of the camera, the first on +x. The reference's GelTip has three on a ring of
/// 12.6 mm.
///
/// ```
/// use yarok_components::tactile::light_fields::led_ring;
///
/// let leds = led_ring(3, 0.0126, 0.010);
/// assert_eq!(leds[0], [0.0126, 0.0, 0.010]);
/// assert!((leds[1][0] + 0.0063).abs() < 1e-12); // 120° on
/// ```
pub fn led_ring(count: usize, radius: f64, z: f64) -> Vec<[f64; 3]> {
    (0..count)
        .map(|i| {
            let angle = std::f64::consts::TAU * i as f64 / count as f64;
            [radius * angle.cos(), radius * angle.sin(), z]
        })
        .collect()
}

/// The tangent of the membrane's cut by the upright plane through the LED and `point`, oriented
/// the way light runs along the cut from the LED: `plane × surface`, with `surface` the
/// membrane's normal on the camera's side and `plane` the plane's normal `(point − led) × axis`.
/// It stays continuous over the tip, where a test against the straight line from the LED would
/// flip it. The straight direction from the LED where that plane is undefined.
fn along_membrane(point: [f64; 3], led: [f64; 3], surface: [f64; 3]) -> [f64; 3] {
    let away = [point[0] - led[0], point[1] - led[1], point[2] - led[2]];
    let axis = [0.0, 0.0, 1.0];
    let plane = normalised(cross(away, axis));
    let tangent = cross(plane, surface);
    let length = dot(tangent, tangent).sqrt();
    if dot(plane, plane) < 0.5 || length < 1e-9 {
        return normalised(away);
    }
    tangent.map(|v| v / length)
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

    /// A hemispherical membrane of radius 12 mm centred 30 mm in front of the camera, bulging
    /// towards it, and a flat wall at 30 mm where rays miss it.
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
    fn linear_fields_are_unit_vectors_pointing_away_from_the_led() {
        let (width, height) = (64, 48);
        let depth = dome(width, height);
        let led = [0.012, 0.0, 0.030];
        let camera = Camera::new(width, height, 70.0);
        let field = light_field(&depth, width, 70.0, led, LightFieldMethod::Linear).unwrap();
        for (i, v) in field.iter().enumerate() {
            let v = v.map(f64::from);
            let z = f64::from(depth[i]);
            let point = camera.point((i % width) as f64, (i / width) as f64, z);
            let away = normalised([point[0] - led[0], point[1] - led[1], point[2] - led[2]]);
            assert!(dot(v, away) > 1.0 - 1e-6, "pixel {i}: {v:?} vs {away:?}");
        }
    }

    /// A GelTip-like finger seen from inside: a tube of radius 12 mm from 10 mm in front of the
    /// camera to 25 mm, closed by a hemispherical tip; per pixel its depth and, where the camera
    /// sees the membrane, its outward normal.
    fn finger(width: usize, height: usize) -> (Vec<f32>, Vec<Option<[f64; 3]>>) {
        let (radius, start, end) = (0.012, 0.010, 0.025);
        let camera = Camera::new(width, height, 70.0);
        (0..width * height)
            .map(|i| {
                let ray = camera.point((i % width) as f64, (i / width) as f64, 1.0);
                let wall = radius / ray[0].hypot(ray[1]);
                if (start..=end).contains(&wall) {
                    let point = camera.point((i % width) as f64, (i / width) as f64, wall);
                    return (wall as f32, Some(normalised([point[0], point[1], 0.0])));
                }
                if wall < start {
                    return (start as f32, None);
                }
                // The far intersection of the ray with the tip's sphere.
                let unit = normalised(ray);
                let b = unit[2] * end;
                let t = b + (b * b - (end * end - radius * radius)).sqrt();
                let point = unit.map(|v| v * t);
                let normal = normalised([point[0], point[1], point[2] - end]);
                ((t * unit[2]) as f32, Some(normal))
            })
            .unzip()
    }

    /// Plane fields are unit vectors along the membrane that turn smoothly from pixel to pixel
    /// away from the LED (around which they radiate), also over the tip, and run away from the
    /// LED on its side; on a finger lit from its base like a GelTip, and on a dome.
    #[test]
    fn plane_fields_are_continuous_tangents() {
        let (width, height) = (96, 72);
        let camera = Camera::new(width, height, 70.0);
        let dome_depth = dome(width, height);
        let dome_normals = (0..width * height)
            .map(|i| {
                let z = f64::from(dome_depth[i]);
                let point = camera.point((i % width) as f64, (i / width) as f64, z);
                (z < 0.0299).then(|| normalised([point[0], point[1], point[2] - 0.030]))
            })
            .collect();
        let shapes = [
            ("finger", finger(width, height), [0.012, 0.0, 0.010]),
            ("dome", (dome_depth, dome_normals), [0.012, 0.0, 0.030]),
        ];
        for (shape, (depth, normals), led) in shapes {
            let field = light_field(&depth, width, 70.0, led, LightFieldMethod::Plane).unwrap();
            let at = |x: usize, y: usize| field[y * width + x].map(f64::from);
            // Inside the image border (where derivatives vanish), neighbours included.
            for y in 1..height - 2 {
                for x in 1..width - 2 {
                    let seen = |u: usize, v: usize| normals[v * width + u].is_some();
                    let around = (y - 1..=y + 1).all(|v| (x - 1..=x + 1).all(|u| seen(u, v)));
                    let Some(normal) = normals[y * width + x].filter(|_| around) else {
                        continue;
                    };
                    let depth = f64::from(depth[y * width + x]);
                    let point = camera.point(x as f64, y as f64, depth);
                    // Around the LED light leaves in every direction: the field is a source.
                    if (point[0] - led[0]).hypot(point[1] - led[1]) < 0.006 {
                        continue;
                    }
                    let (case, v) = (format!("{shape} ({x}, {y})"), at(x, y));
                    assert!((dot(v, v) - 1.0).abs() < 1e-5, "{case}");
                    assert!(dot(v, normal).abs() < 0.15, "{case} leaves the membrane");
                    for (u, w) in [(x + 1, y), (x, y + 1)] {
                        assert!(dot(v, at(u, w)) > 0.5, "{case} → ({u}, {w}) flips");
                    }
                    // Between the LED and the axis, in the LED's plane, light runs away from it.
                    if point[0] > 0.004 && point[1].abs() < 0.003 {
                        let away = [point[0] - led[0], point[1] - led[1], point[2] - led[2]];
                        assert!(dot(v, away) > 0.0, "{case} runs towards the LED");
                    }
                }
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
        )
        .unwrap();
        let linear = light_field(
            &depth,
            width,
            70.0,
            [0.012, 0.0, 0.030],
            LightFieldMethod::Linear,
        )
        .unwrap();
        // At the dome's tip (centre pixel) the surface faces the camera: the plane field is
        // horizontal, while the straight line from the LED dips towards the camera.
        let centre = (height / 2) * width + width / 2;
        assert!(field[centre][2].abs() < 0.05, "{:?}", field[centre]);
        assert!(linear[centre][2] < -0.5, "{:?}", linear[centre]);
    }
}
