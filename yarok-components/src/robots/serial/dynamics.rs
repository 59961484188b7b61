//! [`Dynamics`]: the forces a serial arm's joints need to follow a motion — inertia, gravity,
//! Coriolis and centrifugal forces (MuJoCo's, on a scratch copy of the model's state), the
//! joints' own damping and dry friction — checked against what their actuators give before the
//! motion starts.

use std::sync::Arc;

use yarok_mjc::{Data, JointId, JointLosses, Model};

use crate::robots::profile::Profile;

/// The share of each actuator's strength a motion may plan to use; the rest is left to the
/// feedback that corrects what the plan did not foresee.
pub(super) const PLANNED_SHARE: f64 = 0.9;

/// How many instants of a motion's profile are checked.
const CHECKED_INSTANTS: usize = 60;

/// A joint asked for more force than its actuator gives.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Overload {
    /// Which joint (its index in the arm).
    pub(super) joint: usize,
    /// The force it needs (N·m or N).
    pub(super) needed: f64,
    /// The most the actuator gives that way.
    pub(super) available: f64,
    /// The joint's speed then (rad/s or m/s).
    pub(super) speed: f64,
}

/// One joint's part in the arm's dynamics.
pub(super) struct JointDynamics {
    pub(super) id: JointId,
    pub(super) losses: JointLosses,
    pub(super) force_range: [f64; 2],
}

/// The arm's dynamics, on a scratch state of its own: computing never touches the simulation.
pub(super) struct Dynamics {
    data: Data,
    joints: Vec<JointDynamics>,
    accelerations: Vec<f64>,
    forces: Vec<f64>,
}

impl Dynamics {
    pub(super) fn new(model: &Arc<Model>, joints: Vec<JointDynamics>) -> Result<Self, String> {
        let data = Data::new(model).map_err(|e| e.to_string())?;
        let nv = model.nv();
        Ok(Self {
            data,
            joints,
            accelerations: vec![0.0; nv],
            forces: vec![0.0; nv],
        })
    }

    /// The force each joint needs to be at `q`, moving at `qd` and accelerating at `qdd`
    /// (the rest of the model at its initial state).
    pub(super) fn demand(&mut self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Vec<f64> {
        self.accelerations.fill(0.0);
        for (i, joint) in self.joints.iter().enumerate() {
            self.data.qpos_mut(joint.id)[0] = q[i];
            self.data.qvel_mut(joint.id)[0] = qd[i];
            self.accelerations[self.data.dof(joint.id)] = qdd[i];
        }
        self.data.forward();
        self.data
            .inertia_times(&self.accelerations, &mut self.forces);
        self.joints
            .iter()
            .enumerate()
            .map(|(i, joint)| {
                self.forces[self.data.dof(joint.id)]
                    + self.data.dof_bias_force(joint.id)
                    + joint.losses.damping * qd[i]
                    + joint.losses.frictionloss * qd[i].signum() * f64::from(qd[i] != 0.0)
            })
            .collect()
    }

    /// The worst overload of a motion along `profile` (the joint asked the most for its
    /// strength), its joints at each length along it given by `points` (lengths from 0 to the
    /// profile's end, each with the joints there), if any joint needs more than
    /// [`PLANNED_SHARE`] of its actuator's strength.
    pub(super) fn overload(
        &mut self,
        points: &[(f64, Vec<f64>)],
        profile: &Profile,
    ) -> Option<Overload> {
        let duration = profile.duration();
        let step = duration / CHECKED_INSTANTS as f64;
        let h = (step / 4.0).max(1e-6);
        let mut worst: Option<(f64, Overload)> = None;
        for k in 0..=CHECKED_INSTANTS {
            let t = step * k as f64;
            let (along, speed) = profile.at(t);
            let (_, later) = profile.at(t + h);
            let acceleration = if k == CHECKED_INSTANTS {
                0.0
            } else {
                (later - speed) / h
            };
            let (q, dq, ddq) = joints_at(points, along);
            let qd: Vec<f64> = dq.iter().map(|d| d * speed).collect();
            let qdd: Vec<f64> = dq
                .iter()
                .zip(&ddq)
                .map(|(d, dd)| d * acceleration + dd * speed * speed)
                .collect();
            let demand = self.demand(&q, &qd, &qdd);
            for (joint, (dynamics, &needed)) in self.joints.iter().zip(&demand).enumerate() {
                let [lower, upper] = dynamics.force_range;
                let available = if needed >= 0.0 { upper } else { lower };
                let share = needed.abs() / available.abs();
                if share > PLANNED_SHARE && worst.as_ref().is_none_or(|(most, _)| share > *most) {
                    let overload = Overload {
                        joint,
                        needed,
                        available,
                        speed: qd[joint],
                    };
                    worst = Some((share, overload));
                }
            }
        }
        worst.map(|(_, overload)| overload)
    }
}

/// The joints `along` a path sampled at `points`, and their first and second derivatives with
/// respect to the length, by linear interpolation and finite differences.
fn joints_at(points: &[(f64, Vec<f64>)], along: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = points.len();
    let joints = points[0].1.len();
    if n < 2 {
        return (points[0].1.clone(), vec![0.0; joints], vec![0.0; joints]);
    }
    let i = points
        .windows(2)
        .position(|pair| along <= pair[1].0)
        .unwrap_or(n - 2);
    let ((s0, q0), (s1, q1)) = (&points[i], &points[i + 1]);
    let span = (s1 - s0).max(f64::EPSILON);
    let fraction = ((along - s0) / span).clamp(0.0, 1.0);
    let q = (0..joints)
        .map(|j| q0[j] + (q1[j] - q0[j]) * fraction)
        .collect();
    let slope = |a: usize| -> Vec<f64> {
        let ((sa, qa), (sb, qb)) = (&points[a], &points[a + 1]);
        let span = (sb - sa).max(f64::EPSILON);
        (0..joints).map(|j| (qb[j] - qa[j]) / span).collect()
    };
    let dq = slope(i);
    let ddq = if n >= 3 {
        let (a, b) = if i + 2 < n { (i, i + 1) } else { (i - 1, i) };
        let (first, second) = (slope(a), slope(b));
        let span = ((points[b + 1].0 - points[a].0) / 2.0).max(f64::EPSILON);
        (0..joints).map(|j| (second[j] - first[j]) / span).collect()
    } else {
        vec![0.0; joints]
    };
    (q, dq, ddq)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_sampled_at_points_is_interpolated_with_its_slope_and_curvature() {
        let points: Vec<(f64, Vec<f64>)> = (0..=4)
            .map(|k| {
                let s = k as f64 * 0.25;
                (s, vec![2.0 * s, s * s])
            })
            .collect();
        let (q, dq, ddq) = joints_at(&points, 0.6);
        assert!((q[0] - 1.2).abs() < 1e-12);
        assert!((dq[0] - 2.0).abs() < 1e-12 && ddq[0].abs() < 1e-12);
        assert!((dq[1] - 1.25).abs() < 1e-12, "{dq:?}");
        assert!((ddq[1] - 2.0).abs() < 1e-9, "{ddq:?}");
    }
}
