//! [`Pose`]: where a body or site is.

/// A position and orientation: of a body or site in world coordinates, or of a body in its
/// parent's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position in metres.
    pub pos: [f64; 3],
    /// Orientation as a unit quaternion `[w, x, y, z]`.
    pub quat: [f64; 4],
}

impl Pose {
    /// The `index`th pose of MuJoCo arrays of positions (3 numbers each) and quaternions (4).
    pub(crate) fn of(positions: &[f64], quaternions: &[f64], index: usize) -> Self {
        let mut pose = Pose {
            pos: [0.0; 3],
            quat: [0.0; 4],
        };
        pose.pos
            .copy_from_slice(&positions[3 * index..3 * index + 3]);
        pose.quat
            .copy_from_slice(&quaternions[4 * index..4 * index + 4]);
        pose
    }

    /// `point`, given in world coordinates, in this pose's frame (where a world point lies as
    /// seen from a body or site).
    ///
    /// ```
    /// use yarok_mjc::Pose;
    ///
    /// // A frame 1 m up, turned 90° about z: the world's +x lies along its −y.
    /// let half = std::f64::consts::FRAC_1_SQRT_2;
    /// let pose = Pose { pos: [0.0, 0.0, 1.0], quat: [half, 0.0, 0.0, half] };
    /// let local = pose.to_local([1.0, 0.0, 1.0]);
    /// assert!((local[0]).abs() < 1e-12 && (local[1] + 1.0).abs() < 1e-12 && local[2].abs() < 1e-12);
    /// ```
    pub fn to_local(&self, point: [f64; 3]) -> [f64; 3] {
        let [w, x, y, z] = self.quat;
        let v: [f64; 3] = std::array::from_fn(|axis| point[axis] - self.pos[axis]);
        // Rotates by the conjugate quaternion (w, u), u = −(x, y, z): v + w·t + u × t, t = 2 u × v.
        let u = [-x, -y, -z];
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let t = cross(u, v).map(|c| 2.0 * c);
        let ut = cross(u, t);
        std::array::from_fn(|axis| v[axis] + w * t[axis] + ut[axis])
    }
}
