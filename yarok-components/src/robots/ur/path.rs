//! [`Path`]: where a motion goes — a straight line in joint space (`movej`) or of the TCP in
//! Cartesian space (`movel`) — measured by a length its profile runs along.

use nalgebra::Isometry3;

use super::kinematics::{IkError, Joints, Kinematics};
use crate::robots::paths;

#[derive(Debug, Clone, Copy)]
pub(crate) enum Path {
    /// Every joint moves in proportion; the length is the largest joint motion (radians), so
    /// the leading joint follows the profile.
    Joints { from: Joints, to: Joints },
    /// The TCP moves along a straight line while turning (spherical interpolation); the length
    /// is the longer of the distance (metres) and the turn (radians).
    Line {
        from: Isometry3<f64>,
        to: Isometry3<f64>,
    },
}

/// Where a path is at a point of its length.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Point {
    Joints(Joints),
    Pose(Isometry3<f64>),
}

impl Path {
    pub(crate) fn length(&self) -> f64 {
        match self {
            Path::Joints { from, to } => paths::joints_length(from, to),
            Path::Line { from, to } => paths::line_length(from, to),
        }
    }

    /// The point `along` (0 to [`Path::length`]) the path.
    pub(crate) fn point(&self, along: f64) -> Point {
        let fraction = paths::fraction(along, self.length());
        match self {
            Path::Joints { from, to } => Point::Joints(std::array::from_fn(|i| {
                from[i] + (to[i] - from[i]) * fraction
            })),
            Path::Line { from, to } => Point::Pose(from.lerp_slerp(to, fraction)),
        }
    }

    /// The joints at `point`, by inverse kinematics near `near` for a pose.
    pub(crate) fn joints_at(
        point: Point,
        kinematics: &Kinematics,
        near: &Joints,
    ) -> Result<Joints, IkError> {
        match point {
            Point::Joints(q) => Ok(q),
            Point::Pose(pose) => kinematics.nearest(&pose, near),
        }
    }

    /// Checks, before anything moves, that the arm can follow the whole path from `start`:
    /// a line's end within reach first, then every point of it reachable within the joint
    /// limits, without a joint jumping (a singularity or a change of branch on the way).
    /// Returns the joints at the end.
    pub(crate) fn check(
        &self,
        kinematics: &Kinematics,
        start: &Joints,
    ) -> Result<Joints, PathError> {
        if let Path::Line { to, .. } = self {
            kinematics.nearest(to, start)?;
        }
        paths::check(
            self.length(),
            matches!(self, Path::Line { .. }),
            *start,
            |along, near| Ok(Self::joints_at(self.point(along), kinematics, near)?),
            |along, jump| PathError::Singular { along, jump },
        )
        .map(|points| points.last().map_or(*start, |&(_, end)| end))
    }
}

/// Why a path cannot be followed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PathError {
    /// A point of the path has no joint solution.
    #[error(transparent)]
    Kinematics(#[from] IkError),
    /// The joints would jump on the way.
    #[error(
        "the line passes a singularity {along:.3} along its length (a joint would jump {jump:.2} rad)"
    )]
    Singular {
        /// How far along the path (metres or radians).
        along: f64,
        /// The jump (radians).
        jump: f64,
    },
}
