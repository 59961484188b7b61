//! [`SimState`]: a `sim` world's joints and transform frames, as the recorder and the bridge
//! publish them.

use yarok_mjc::{BodyId, CameraId, JointId, Pose, SimBackend};

/// Which joints and frames a model has, found once, and their state.
///
/// The joints are those of one coordinate (hinges and slides), named by their name or, when
/// they have none, by their body's (`block/joint`); a free or ball joint moves its body, whose
/// frame has the pose. The frames are every named body's, then every named camera's optical
/// frame, `{camera}/optical` (+x right and +y down in the image, +z forward), the frame its
/// images are in.
#[derive(Debug, Default)]
pub(crate) struct SimState {
    joints: Vec<JointId>,
    joint_names: Vec<String>,
    bodies: Vec<BodyId>,
    cameras: Vec<CameraId>,
    frame_names: Vec<String>,
}

/// The suffix of a camera's optical frame.
const OPTICAL: &str = "/optical";

/// The name of camera `camera`'s optical frame.
pub(super) fn optical_frame(camera: &str) -> String {
    format!("{camera}{OPTICAL}")
}

impl SimState {
    /// The joints and frames of `sim`'s model.
    pub(crate) fn of(sim: &SimBackend) -> Self {
        let model = sim.model();
        let data = sim.data();
        let mut state = Self::default();
        for (index, joint) in model.joints().enumerate() {
            if data.qpos(joint).len() != 1 {
                continue;
            }
            let name = model.joint_name(joint).unwrap_or_else(|| {
                model
                    .body_name(model.joint_body(joint))
                    .map_or_else(|| format!("joint{index}"), |body| format!("{body}/joint"))
            });
            state.joints.push(joint);
            state.joint_names.push(name);
        }
        for body in model.bodies() {
            if let Some(name) = model.body_name(body) {
                state.bodies.push(body);
                state.frame_names.push(name);
            }
        }
        for camera in model.cameras() {
            if let Some(name) = model.camera_name(camera) {
                state.cameras.push(camera);
                state.frame_names.push(optical_frame(&name));
            }
        }
        state
    }

    /// The joints' names.
    pub(crate) fn joint_names(&self) -> &[String] {
        &self.joint_names
    }

    /// The frames' names, in the order of [`SimState::poses`].
    pub(super) fn frame_names(&self) -> &[String] {
        &self.frame_names
    }

    /// The frame a component's images are in: its camera's optical frame when it has one
    /// camera (component `/arm/gripper/left_digit`, camera `arm/gripper/left_digit/camera`),
    /// else its first body's frame, else the world's.
    pub(super) fn frame_of_component(&self, component: &str) -> String {
        let prefix = format!("{}/", component.trim_start_matches('/'));
        let within = |name: &&String| name.starts_with(&prefix);
        let mut cameras = self.frame_names[self.bodies.len()..].iter().filter(within);
        if let (Some(camera), None) = (cameras.next(), cameras.next()) {
            return camera.clone();
        }
        self.frame_names[..self.bodies.len()]
            .iter()
            .find(within)
            .cloned()
            .unwrap_or_else(|| "world".to_owned())
    }

    /// Every joint's position and velocity now.
    pub(crate) fn joint_values(&self, sim: &SimBackend) -> (Vec<f64>, Vec<f64>) {
        let data = sim.data();
        self.joints
            .iter()
            .map(|joint| (data.qpos(*joint)[0], data.qvel(*joint)[0]))
            .unzip()
    }

    /// Every frame's pose in the world frame now.
    pub(super) fn poses(&self, sim: &SimBackend) -> Vec<Pose> {
        let data = sim.data();
        let bodies = self.bodies.iter().map(|body| data.body_pose(*body));
        let cameras = self
            .cameras
            .iter()
            .map(|camera| optical(data.camera_pose(*camera)));
        bodies.chain(cameras).collect()
    }
}

/// A MuJoCo camera's pose (looking down −z, +y up) turned half a turn about its x axis: the
/// optical frame's (looking down +z, +y down).
fn optical(camera: Pose) -> Pose {
    let [w, x, y, z] = camera.quat;
    // camera ⊗ (0, 1, 0, 0), the half turn about x.
    Pose {
        pos: camera.pos,
        quat: [-x, w, z, -y],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `v` turned by unit quaternion `q` (w, x, y, z): into the local frame of the inverse turn.
    fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
        let [w, x, y, z] = q;
        Pose {
            pos: [0.0; 3],
            quat: [w, -x, -y, -z],
        }
        .to_local(v)
    }

    #[test]
    fn the_optical_frame_looks_where_the_camera_looks_with_y_down() {
        // A camera turned a quarter about z: it looks down world −z, its image's up is world −x.
        let half = std::f64::consts::FRAC_1_SQRT_2;
        let camera = Pose {
            pos: [1.0, 2.0, 3.0],
            quat: [half, 0.0, 0.0, half],
        };
        let optical = optical(camera);
        assert_eq!(optical.pos, camera.pos);
        let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(a, b)| (a - b).abs() < 1e-12);
        let forward = rotate(camera.quat, [0.0, 0.0, -1.0]);
        let up = rotate(camera.quat, [0.0, 1.0, 0.0]);
        let right = rotate(camera.quat, [1.0, 0.0, 0.0]);
        assert!(close(rotate(optical.quat, [0.0, 0.0, 1.0]), forward));
        assert!(close(rotate(optical.quat, [0.0, 1.0, 0.0]), up.map(|c| -c)));
        assert!(close(rotate(optical.quat, [1.0, 0.0, 0.0]), right));
    }
}
