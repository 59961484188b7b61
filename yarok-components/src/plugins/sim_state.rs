//! [`SimState`]: a `sim` world's joint coordinates and named bodies, as the recorder and the
//! bridge publish them.

use yarok_mjc::{BodyId, JointId, Pose, SimBackend};

use super::recording_profile::JointValues;

/// Which joints and bodies a model has, found once, and their state.
#[derive(Debug, Default)]
pub(super) struct SimState {
    joints: Vec<JointId>,
    /// A name per joint coordinate: the joint's, or `joint[k]` for joints of several.
    coordinate_names: Vec<String>,
    bodies: Vec<(BodyId, String)>,
}

impl SimState {
    /// The joints and named bodies of `sim`'s model.
    pub(super) fn of(sim: &SimBackend) -> Self {
        let model = sim.model();
        let data = sim.data();
        let mut state = Self::default();
        for (index, joint) in model.joints().enumerate() {
            let name = model
                .joint_name(joint)
                .unwrap_or_else(|| format!("joint{index}"));
            let count = data.qpos(joint).len();
            state.coordinate_names.extend((0..count).map(|k| {
                if count > 1 {
                    format!("{name}[{k}]")
                } else {
                    name.clone()
                }
            }));
            state.joints.push(joint);
        }
        state.bodies = model
            .bodies()
            .filter_map(|body| model.body_name(body).map(|name| (body, name)))
            .collect();
        state
    }

    /// Every joint coordinate's name, position and velocity now.
    pub(super) fn joint_values(&self, sim: &SimBackend) -> JointValues<'_> {
        let data = sim.data();
        let mut positions = Vec::with_capacity(self.coordinate_names.len());
        let mut velocities = Vec::with_capacity(self.coordinate_names.len());
        for joint in &self.joints {
            positions.extend_from_slice(data.qpos(*joint));
            velocities.extend_from_slice(data.qvel(*joint));
        }
        JointValues {
            names: &self.coordinate_names,
            positions,
            velocities,
        }
    }

    /// Every named body's pose in the world frame now.
    pub(super) fn poses(&self, sim: &SimBackend) -> Vec<(&str, Pose)> {
        let data = sim.data();
        self.bodies
            .iter()
            .map(|(body, name)| (name.as_str(), data.body_pose(*body)))
            .collect()
    }
}
