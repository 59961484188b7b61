//! Closed-form kinematics of the Universal Robots arms: forward kinematics from the standard
//! Denavit–Hartenberg parameters and every inverse solution (up to eight), after K. P. Hawkins,
//! "Analytic Inverse Kinematics for the Universal Robots UR-5/UR-10 Arms" (2013).
//!
//! Poses are of the `tool0` frame (DH frame 6: origin on the flange face, z out of the flange)
//! in the arm's base frame (DH frame 0: z up along joint 1, the arm stretched along −x at
//! q = 0), which are the UR controller's base and tool frames with a zero TCP.

use std::f64::consts::{PI, TAU};

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};

/// Six joint angles in radians, base to wrist 3.
pub type Joints = [f64; 6];

/// The standard DH parameters of a UR-family arm (metres): `a1 = 0`, `α = (π/2, 0, 0, π/2,
/// −π/2, 0)`, `d2 = d3 = 0`, all θ offsets 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DhParameters {
    /// Base to shoulder height.
    pub d1: f64,
    /// Upper arm length (negative: the arm stretches along −x).
    pub a2: f64,
    /// Forearm length (negative).
    pub a3: f64,
    /// Shoulder offset left after the elbow (wrist 1 along its axis).
    pub d4: f64,
    /// Wrist 1 to wrist 2.
    pub d5: f64,
    /// Wrist 2 axis to the flange face.
    pub d6: f64,
}

impl DhParameters {
    /// UR5 (CB3, "series 3"), as in its manual's appendix C.
    pub const UR5: Self = Self {
        d1: 0.089159,
        a2: -0.425,
        a3: -0.39225,
        d4: 0.10915,
        d5: 0.09465,
        d6: 0.0823,
    };

    /// UR5e.
    pub const UR5E: Self = Self {
        d1: 0.1625,
        a2: -0.425,
        a3: -0.3922,
        d4: 0.1333,
        d5: 0.0997,
        d6: 0.0996,
    };

    /// `(d, a, α)` of link `i` (0-based).
    pub fn link(&self, i: usize) -> (f64, f64, f64) {
        const HALF: f64 = PI / 2.0;
        match i {
            0 => (self.d1, 0.0, HALF),
            1 => (0.0, self.a2, 0.0),
            2 => (0.0, self.a3, 0.0),
            3 => (self.d4, 0.0, HALF),
            4 => (self.d5, 0.0, -HALF),
            _ => (self.d6, 0.0, 0.0),
        }
    }

    /// The fixed part of link `i`'s transform, `Tz(d)·Tx(a)·Rx(α)`: where joint `i + 1`'s frame
    /// (at angle 0) sits in joint `i`'s.
    pub fn link_offset(&self, i: usize) -> Isometry3<f64> {
        self.frame(i, 1.0, 0.0).isometry()
    }

    /// DH frame `i + 1` in DH frame `i` with joint `i` at the angle of cosine `c` and sine `s`:
    /// `Rz(θ)·Tz(d)·Tx(a)·Rx(α)`, with α's sine and cosine exact.
    fn frame(&self, i: usize, c: f64, s: f64) -> Frame {
        /// Sine and cosine of each link's α (π/2, 0, 0, π/2, −π/2, 0), exactly.
        const ALPHA: [(f64, f64); 6] = [
            (1.0, 0.0),
            (0.0, 1.0),
            (0.0, 1.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, 1.0),
        ];
        let (d, a, _) = self.link(i);
        let (sa, ca) = ALPHA[i.min(5)];
        Frame {
            rotation: Matrix3::new(c, -s * ca, s * sa, s, c * ca, -c * sa, 0.0, sa, ca),
            translation: Vector3::new(a * c, a * s, d),
        }
    }

    /// `tool0` in the base frame at joint angles `q`.
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_components::robots::ur::DhParameters;
    ///
    /// // Upright: the flange points up, above the base.
    /// let q = [0.0, -std::f64::consts::FRAC_PI_2, 0.0, -std::f64::consts::FRAC_PI_2, 0.0, 0.0];
    /// let tool0 = DhParameters::UR5E.forward(&q);
    /// assert!((tool0.translation.z - 1.0794).abs() < 1e-4);
    /// ```
    pub fn forward(&self, q: &Joints) -> Isometry3<f64> {
        (0..6)
            .fold(Frame::IDENTITY, |frame, i| {
                let (s, c) = q[i].sin_cos();
                frame.then(&self.frame(i, c, s))
            })
            .isometry()
    }

    /// Every joint solution that puts `tool0` at `pose` (up to eight; none when it is out of
    /// reach), each angle in (−π, π]. At a wrist singularity (joints 4 and 6 aligned) wrist 3
    /// is free and takes `free_wrist_3`.
    pub fn inverse(&self, pose: &Isometry3<f64>, free_wrist_3: f64) -> Solutions {
        let mut solutions = Solutions::default();
        if !is_finite(pose) {
            return solutions;
        }
        let tool0 = Frame {
            rotation: pose.rotation.to_rotation_matrix().into_inner(),
            translation: pose.translation.vector,
        };
        let rotation = &tool0.rotation;
        let (x, y, z) = (rotation.column(0), rotation.column(1), rotation.column(2));
        // The point on joint 5's axis: one d6 back from the flange.
        let wrist = tool0.translation - self.d6 * z;
        let radius = wrist.x.hypot(wrist.y);
        let Some(shoulder) = within_unit(self.d4 / radius).map(f64::acos) else {
            return solutions;
        };
        // θ1 = heading + π/2 ± shoulder; its cosine and sine by angle addition.
        let heading = wrist.y.atan2(wrist.x) + PI / 2.0;
        let (ch, sh) = (-wrist.y / radius, wrist.x / radius);
        let (cs, ss) = (shoulder.cos(), shoulder.sin());
        for (theta1, c1, s1) in [
            (heading + shoulder, ch * cs - sh * ss, sh * cs + ch * ss),
            (heading - shoulder, ch * cs + sh * ss, sh * cs - ch * ss),
        ] {
            // The flange's z axis along joint 2's axis (frame 1's z) is cos θ5.
            let tool0_in_1 = self.frame(0, c1, s1).inverse().then(&tool0);
            let c5 = (s1 * z.x - c1 * z.y).clamp(-1.0, 1.0);
            let (theta5, sine5) = (c5.acos(), (1.0 - c5 * c5).sqrt());
            for (theta5, s5) in [(theta5, sine5), (-theta5, -sine5)] {
                let wrist3 = if s5.abs() < SINGULAR {
                    let (s6, c6) = free_wrist_3.sin_cos();
                    (free_wrist_3, c6, s6)
                } else {
                    let (s6, c6) = (-(s1 * y.x - c1 * y.y) / s5, (s1 * x.x - c1 * x.y) / s5);
                    let norm = s6.hypot(c6);
                    (s6.atan2(c6), c6 / norm, s6 / norm)
                };
                let wrist = Wrist {
                    theta1,
                    theta5,
                    c5,
                    s5,
                    wrist3,
                };
                self.solve_planar(&wrist, &tool0_in_1, &mut solutions);
            }
        }
        solutions
    }

    /// Joints 2, 3 and 4 (parallel axes) once θ1, θ5 and θ6 are known: both elbows.
    /// `tool0_in_1` is `tool0` in DH frame 1 (θ1 undone).
    fn solve_planar(&self, wrist: &Wrist, tool0_in_1: &Frame, solutions: &mut Solutions) {
        let (theta6, c6, s6) = wrist.wrist3;
        let frame4 = tool0_in_1
            .then(&self.frame(5, c6, s6).inverse())
            .then(&self.frame(4, wrist.c5, wrist.s5).inverse());
        let planar = frame4.translation;
        let (a2, a3) = (self.a2, self.a3);
        let Some(c3) = within_unit(
            (planar.x * planar.x + planar.y * planar.y - a2 * a2 - a3 * a3) / (2.0 * a2 * a3),
        ) else {
            return;
        };
        let (elbow, s3) = (c3.acos(), (1.0 - c3 * c3).sqrt());
        let sum = frame4.rotation[(1, 0)].atan2(frame4.rotation[(0, 0)]);
        for (theta3, s3) in [(elbow, s3), (-elbow, -s3)] {
            // θ2 = atan2(planar) − atan2(a3·s3, a2 + a3·c3), as one angle difference.
            let (along, across) = (a2 + a3 * c3, a3 * s3);
            let theta2 =
                (planar.y * along - planar.x * across).atan2(planar.x * along + planar.y * across);
            let theta4 = sum - theta2 - theta3;
            let q = [wrist.theta1, theta2, theta3, theta4, wrist.theta5, theta6];
            solutions.push(q.map(wrap));
        }
    }
}

/// θ1, θ5 and θ6 of a branch, with the cosines and sines the rest of the solve uses.
struct Wrist {
    theta1: f64,
    theta5: f64,
    c5: f64,
    s5: f64,
    /// θ6, its cosine and sine.
    wrist3: (f64, f64, f64),
}

/// A rigid transform as a rotation matrix and a translation: cheaper to compose than
/// quaternions where sines and cosines are at hand.
#[derive(Debug, Clone, Copy)]
struct Frame {
    rotation: Matrix3<f64>,
    translation: Vector3<f64>,
}

impl Frame {
    const IDENTITY: Self = Self {
        rotation: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        translation: Vector3::new(0.0, 0.0, 0.0),
    };

    /// `self · next`.
    fn then(&self, next: &Frame) -> Frame {
        Frame {
            rotation: self.rotation * next.rotation,
            translation: self.rotation * next.translation + self.translation,
        }
    }

    fn inverse(&self) -> Frame {
        let rotation = self.rotation.transpose();
        Frame {
            translation: -(rotation * self.translation),
            rotation,
        }
    }

    fn isometry(&self) -> Isometry3<f64> {
        let rotation = Rotation3::from_matrix_unchecked(self.rotation);
        Isometry3::from_parts(
            Translation3::from(self.translation),
            UnitQuaternion::from_rotation_matrix(&rotation),
        )
    }
}

/// `|sin θ5|` below which the wrist counts as singular (wrist 3 free).
const SINGULAR: f64 = 1e-10;

/// `value` clamped to [−1, 1] if within rounding of it; `None` beyond (out of reach).
fn within_unit(value: f64) -> Option<f64> {
    const ROUNDING: f64 = 1e-9;
    (value.abs() <= 1.0 + ROUNDING).then(|| value.clamp(-1.0, 1.0))
}

/// `angle` in (−π, π].
fn wrap(angle: f64) -> f64 {
    let wrapped = angle.rem_euclid(TAU);
    if wrapped > PI { wrapped - TAU } else { wrapped }
}

fn is_finite(pose: &Isometry3<f64>) -> bool {
    pose.translation.vector.iter().all(|v| v.is_finite())
        && pose.rotation.coords.iter().all(|v| v.is_finite())
}

/// Up to eight joint solutions, in the order θ1 branch, then wrist flip, then elbow.
#[derive(Debug, Clone, Copy, Default)]
pub struct Solutions {
    joints: [Joints; 8],
    len: usize,
}

impl Solutions {
    fn push(&mut self, q: Joints) {
        if self.len < self.joints.len() && q.iter().all(|v| v.is_finite()) {
            self.joints[self.len] = q;
            self.len += 1;
        }
    }

    /// The solutions.
    pub fn as_slice(&self) -> &[Joints] {
        &self.joints[..self.len]
    }

    /// How many there are.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there is none (the pose is out of reach).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// Joint limits in radians, `(lower, upper)` per joint.
pub type JointLimits = [(f64, f64); 6];

/// Why no joint solution was returned.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IkError {
    /// The pose is out of the arm's reach (or inside the shoulder's cylinder).
    #[error("the pose {pose:?} (x y z rx ry rz, base frame) is out of the arm's reach")]
    Unreachable {
        /// The pose asked for, as a UR pose vector.
        pose: [f64; 6],
    },
    /// Every solution puts a joint outside its limits.
    #[error("the pose {pose:?} (x y z rx ry rz, base frame) needs a joint outside its limits")]
    OutsideLimits {
        /// The pose asked for, as a UR pose vector.
        pose: [f64; 6],
    },
    /// A coordinate of the pose or of the current joints is NaN or infinite.
    #[error("the pose {pose:?} or the current joints {current:?} are not finite")]
    NotFinite {
        /// The pose asked for.
        pose: [f64; 6],
        /// The joints the solution was to be near.
        current: Joints,
    },
}

/// A UR arm's kinematics: its DH parameters, joint limits and tool centre point (TCP, in the
/// `tool0` frame). Poses are of the TCP in the base frame.
///
/// # Examples
///
/// ```
/// use yarok_components::robots::ur::{DhParameters, Kinematics, pose_from_vector};
///
/// let kinematics = Kinematics::new(DhParameters::UR5E);
/// let home = [-1.5708, -1.5708, 1.5708, -1.5708, -1.5708, 0.0];
/// let target = pose_from_vector([-0.2, 0.45, 0.3, std::f64::consts::PI, 0.0, 0.0]);
/// let q = kinematics.nearest(&target, &home)?;
/// let reached = kinematics.forward(&q);
/// assert!((reached.translation.vector - target.translation.vector).norm() < 1e-9);
/// # Ok::<(), yarok_components::robots::ur::IkError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// The arm's DH parameters.
    pub dh: DhParameters,
    /// Joint limits (radians); ±2π copies of a solution are tried within them.
    pub limits: JointLimits,
    /// The tool centre point in the `tool0` frame.
    pub tcp: Isometry3<f64>,
}

impl Kinematics {
    /// Every joint at ±2π (as the real arms), the elbow at ±π (its cable and links make more
    /// impossible), and a zero TCP.
    pub fn new(dh: DhParameters) -> Self {
        let full = (-TAU, TAU);
        Self {
            dh,
            limits: [full, full, (-PI, PI), full, full, full],
            tcp: Isometry3::identity(),
        }
    }

    /// The same kinematics with the TCP at `tcp` in the `tool0` frame.
    #[must_use]
    pub fn with_tcp(mut self, tcp: Isometry3<f64>) -> Self {
        self.tcp = tcp;
        self
    }

    /// The same kinematics with other joint limits.
    #[must_use]
    pub fn with_limits(mut self, limits: JointLimits) -> Self {
        self.limits = limits;
        self
    }

    /// The TCP in the base frame at joint angles `q`.
    pub fn forward(&self, q: &Joints) -> Isometry3<f64> {
        self.dh.forward(q) * self.tcp
    }

    /// Every solution that puts the TCP at `pose` within the joint limits, each joint at the
    /// ±2π copy nearest `current`; a free wrist 3 (at a wrist singularity) keeps `current[5]`.
    pub fn solutions(&self, pose: &Isometry3<f64>, current: &Joints) -> Vec<Joints> {
        let tool0 = pose * self.tcp.inverse();
        self.dh
            .inverse(&tool0, current[5])
            .as_slice()
            .iter()
            .filter_map(|q| self.within_limits(q, current))
            .collect()
    }

    /// The solution nearest `current` (least sum of joint motions) that puts the TCP at `pose`
    /// within the joint limits.
    ///
    /// # Errors
    ///
    /// [`IkError`]: out of reach, outside the limits, or not finite.
    pub fn nearest(&self, pose: &Isometry3<f64>, current: &Joints) -> Result<Joints, IkError> {
        if !is_finite(pose) || current.iter().any(|q| !q.is_finite()) {
            return Err(IkError::NotFinite {
                pose: pose_to_vector(pose),
                current: *current,
            });
        }
        let tool0 = pose * self.tcp.inverse();
        let solutions = self.dh.inverse(&tool0, current[5]);
        if solutions.is_empty() {
            return Err(IkError::Unreachable {
                pose: pose_to_vector(pose),
            });
        }
        let mut nearest = None;
        let mut least = f64::INFINITY;
        for q in solutions.as_slice() {
            if let Some(q) = self.within_limits(q, current) {
                let motion = distance(&q, current);
                if motion < least {
                    (nearest, least) = (Some(q), motion);
                }
            }
        }
        nearest.ok_or_else(|| IkError::OutsideLimits {
            pose: pose_to_vector(pose),
        })
    }

    /// `q` with each joint at its ±2π copy nearest `current` within the limits; `None` when a
    /// joint has no copy within them.
    fn within_limits(&self, q: &Joints, current: &Joints) -> Option<Joints> {
        let mut chosen = [0.0; 6];
        for (i, slot) in chosen.iter_mut().enumerate() {
            let (lower, upper) = self.limits[i];
            let inside = |angle: &f64| (lower..=upper).contains(angle);
            // The copy nearest the current angle, else the nearer of those a turn either side.
            let nearest = q[i] + TAU * nearest_integer((current[i] - q[i]) / TAU);
            let (near, far) = if nearest > current[i] {
                (nearest - TAU, nearest + TAU)
            } else {
                (nearest + TAU, nearest - TAU)
            };
            *slot = [nearest, near, far].into_iter().find(inside)?;
        }
        Some(chosen)
    }
}

/// The integer nearest `x` (finite, well within `i64`), without a library call on CPUs
/// without SSE4.1's rounding instructions.
fn nearest_integer(x: f64) -> f64 {
    let shifted = x + 0.5;
    let truncated = shifted as i64 as f64;
    if truncated > shifted {
        truncated - 1.0
    } else {
        truncated
    }
}

fn distance(a: &Joints, b: &Joints) -> f64 {
    a.iter().zip(b).map(|(a, b)| (a - b).abs()).sum()
}

/// The pose a UR pose vector `[x, y, z, rx, ry, rz]` (metres; rotation vector in radians, its
/// direction the axis and its length the angle) stands for.
pub fn pose_from_vector([x, y, z, rx, ry, rz]: [f64; 6]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(x, y, z),
        UnitQuaternion::from_scaled_axis(Vector3::new(rx, ry, rz)),
    )
}

/// The UR pose vector `[x, y, z, rx, ry, rz]` of `pose` (rotation angle in [0, π]).
pub fn pose_to_vector(pose: &Isometry3<f64>) -> [f64; 6] {
    let p = pose.translation.vector;
    let r = pose.rotation.scaled_axis();
    [p.x, p.y, p.z, r.x, r.y, r.z]
}
