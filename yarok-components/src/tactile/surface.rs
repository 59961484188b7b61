//! Surface geometry shared by the GelTip model and its light fields: a pinhole camera that
//! back-projects depth rows into points, surface normals from neighbouring rows, and small
//! vector helpers.

/// A pinhole camera: focal length and centre, in pixels.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Camera {
    f: f64,
    cx: f64,
    cy: f64,
}

impl Camera {
    /// The camera of an image `width × height` with vertical field of view `fov_deg` (square
    /// pixels; the centre between the middle pixels).
    pub(crate) fn new(width: usize, height: usize, fov_deg: f64) -> Self {
        Self {
            f: height as f64 / (2.0 * (fov_deg.to_radians() / 2.0).tan()),
            cx: (width as f64 - 1.0) / 2.0,
            cy: (height as f64 - 1.0) / 2.0,
        }
    }

    /// The point pixel `(u, v)` sees at depth `z` (along the camera axis).
    pub(crate) fn point(self, u: f64, v: f64, z: f64) -> [f64; 3] {
        [(u - self.cx) * z / self.f, (v - self.cy) * z / self.f, z]
    }
}

/// Row `row` of camera-frame points (x, y, z planes) from depths along the camera axis, scaled
/// by `scale`.
#[inline(always)]
pub(crate) fn back_project_row(
    camera: Camera,
    row: usize,
    depth: &[f32],
    scale: f64,
    [px, py, pz]: &mut [Vec<f64>; 3],
) {
    let v = row as f64;
    let mut u = 0.0;
    for (((x, y), z), d) in px
        .iter_mut()
        .zip(py.iter_mut())
        .zip(pz.iter_mut())
        .zip(depth)
    {
        [*x, *y, *z] = camera.point(u, v, f64::from(*d) * scale);
        u += 1.0;
    }
}

/// Surface normals `−(t̂x × t̂y)` of the middle of three rows of points, from central differences
/// along the row (`tangent` is its scratch) and across the rows, with reflect-101 borders.
#[inline(always)]
pub(crate) fn normals_row(
    [above, row, below]: [&[Vec<f64>; 3]; 3],
    tangent: &mut [Vec<f64>; 3],
    [nx, ny, nz]: &mut [Vec<f64>; 3],
) {
    let width = nx.len();
    for (t, p) in tangent.iter_mut().zip(row) {
        t[0] = 0.0;
        t[width - 1] = 0.0;
        if width > 2 {
            for (t, (right, left)) in t[1..width - 1]
                .iter_mut()
                .zip(p[2..].iter().zip(&p[..width - 2]))
            {
                *t = (right - left) / 2.0;
            }
        }
    }
    let [tx, ty, tz] = &*tangent;
    let along = tx.iter().zip(ty).zip(tz);
    let up = above[0].iter().zip(&above[1]).zip(&above[2]);
    let down = below[0].iter().zip(&below[1]).zip(&below[2]);
    let normals = nx.iter_mut().zip(ny.iter_mut()).zip(nz.iter_mut());
    for ((((x, y), z), ((ax, ay), az)), (((ux, uy), uz), ((dx, dy), dz))) in
        normals.zip(along).zip(up.zip(down))
    {
        let across = [(dx - ux) / 2.0, (dy - uy) / 2.0, (dz - uz) / 2.0];
        [*x, *y, *z] = surface_normal([*ax, *ay, *az], across);
    }
}

/// The surface normal from a pair of tangents, `−(t̂x × t̂y)` as the reference computes it.
#[inline(always)]
fn surface_normal(tx: [f64; 3], ty: [f64; 3]) -> [f64; 3] {
    let (a, b) = (normalised(tx), normalised(ty));
    [
        -(a[1] * b[2] - a[2] * b[1]),
        -(a[2] * b[0] - a[0] * b[2]),
        -(a[0] * b[1] - a[1] * b[0]),
    ]
}

#[inline(always)]
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
pub(crate) fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// The unit vector along `a`; vectors shorter than 1e-9 are left as they are, as in the reference.
#[inline(always)]
pub(crate) fn normalised(a: [f64; 3]) -> [f64; 3] {
    let norm = dot(a, a).sqrt();
    let inverse = if norm < 1e-9 { 1.0 } else { 1.0 / norm };
    scale(a, inverse)
}
