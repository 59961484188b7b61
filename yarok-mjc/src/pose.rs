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
}
