//! [`Features`]: a world's observation and action as a policy sees them and a LeRobot dataset
//! records them (beside the plugins, which record and show them) — `observation.state`, `observation.environment_state`,
//! `observation.images.*` and `action`, with the same names and shapes everywhere.

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_core::runtime::World;
use yarok_mjc::{ActuatorId, JointId};

use super::model_cameras::ModelCameras;
use super::sim_state::SimState;

/// The numbers of a free body's pose in `observation.environment_state`: position, then
/// orientation as a unit quaternion (w first, as MuJoCo's).
pub const POSE_PARTS: [&str; 7] = ["x", "y", "z", "qw", "qx", "qy", "qz"];

/// An RGB image feature: its key and size, and the probe it comes from (or none: a camera of
/// the model).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ImageFeature {
    /// `observation.images.arm.gripper.left_digit.image`.
    pub key: String,
    /// Columns and rows.
    pub size: [u32; 2],
    /// The index of its probe among [`World::probes`].
    probe: Option<usize>,
}

/// A `sim` world's features, found once when it starts:
/// - `observation.state`: every hinge's and slide's position, named as in the model;
/// - `observation.environment_state`: every free body's pose ([`POSE_PARTS`] each, named
///   `medium/x` … `medium/qz`): where the objects are;
/// - `observation.images.{probe}`: every RGB probe's image (`observation.images.arm.gripper.left_digit.image`),
///   then `observation.images.{camera}` for each camera of the model asked for
///   (`observation.images.overview`);
/// - `action`: every component's actuation ([`World::actuations`]: an arm's joint targets, a
///   gripper's position), then the raw control of every actuator no actuation drives.
#[derive(Debug)]
pub struct Features {
    sim: SimState,
    free_joints: Vec<JointId>,
    environment_names: Vec<String>,
    images: Vec<ImageFeature>,
    cameras: ModelCameras,
    action_names: Vec<String>,
    action_ranges: Vec<[f64; 2]>,
    /// The actuators driven by their control input directly.
    raw_actuators: Vec<ActuatorId>,
}

/// One observation of a world: the numbers of each feature and the images.
#[derive(Debug, Clone, PartialEq)]
pub struct Observation {
    /// `observation.state`.
    pub state: Vec<f64>,
    /// `observation.environment_state`.
    pub environment_state: Vec<f64>,
    /// `observation.images.*`, in [`Features::images`]' order: RGB rows, top first.
    pub images: Vec<Vec<u8>>,
}

/// The key of the image feature of probe or camera `path` (`/arm/left/image`, `overview`):
/// `observation.images.arm.left.image`.
pub fn image_key(path: &str) -> String {
    format!(
        "observation.images.{}",
        path.trim_start_matches('/').replace('/', ".")
    )
}

impl Features {
    /// The features of `world`, a `sim` world that has started, with the model's `cameras`
    /// rendered at `size` (with MuJoCo's shadows and reflections when `quality`).
    ///
    /// # Errors
    ///
    /// When the world is not simulated, a probe cannot be read, the model has no camera of a
    /// name, or the renderer cannot be made.
    pub fn of(
        world: &World<'_>,
        cameras: &[String],
        size: [u32; 2],
        quality: bool,
    ) -> Result<Self, BoxError> {
        let sim = super::sim_backend(world)?;
        let model = sim.model();
        let data = sim.data();
        let mut free_joints = Vec::new();
        let mut environment_names = Vec::new();
        for (index, joint) in model.joints().enumerate() {
            if data.qpos(joint).len() != POSE_PARTS.len() {
                continue;
            }
            let body = model
                .body_name(model.joint_body(joint))
                .unwrap_or_else(|| format!("free{index}"));
            free_joints.push(joint);
            environment_names.extend(POSE_PARTS.iter().map(|part| format!("{body}/{part}")));
        }
        drop(data);
        let mut images = Vec::new();
        for (probe, named) in world.probes().iter().enumerate() {
            if let ProbeImage::Rgb { width, height, .. } = named.read()? {
                images.push(ImageFeature {
                    key: image_key(&named.path()),
                    size: [width, height],
                    probe: Some(probe),
                });
            }
        }
        images.extend(cameras.iter().map(|camera| ImageFeature {
            key: image_key(camera),
            size,
            probe: None,
        }));
        let mut action_names: Vec<String> = world
            .actuations()
            .iter()
            .flat_map(|actuation| actuation.names().iter().cloned())
            .collect();
        let mut action_ranges: Vec<[f64; 2]> = world
            .actuations()
            .iter()
            .flat_map(|actuation| actuation.ranges().iter().copied())
            .collect();
        let driven: Vec<String> = world
            .actuations()
            .iter()
            .map(|actuation| format!("{}/", actuation.component().trim_start_matches('/')))
            .collect();
        let mut raw_actuators = Vec::new();
        for (index, actuator) in model.actuators().enumerate() {
            let name = model
                .actuator_name(actuator)
                .unwrap_or_else(|| format!("actuator{index}"));
            if !driven.iter().any(|prefix| name.starts_with(prefix)) {
                raw_actuators.push(actuator);
                action_names.push(name);
                let unbounded = [f64::NEG_INFINITY, f64::INFINITY];
                action_ranges.push(model.ctrl_range(actuator).unwrap_or(unbounded));
            }
        }
        Ok(Self {
            sim: SimState::of(sim),
            free_joints,
            environment_names,
            images,
            cameras: ModelCameras::find(sim, cameras, size, quality)?,
            action_names,
            action_ranges,
            raw_actuators,
        })
    }

    /// `observation.state`'s names: the joints.
    pub fn state_names(&self) -> &[String] {
        self.sim.joint_names()
    }

    /// `observation.environment_state`'s names: the free bodies' pose numbers.
    pub fn environment_names(&self) -> &[String] {
        &self.environment_names
    }

    /// The image features.
    pub fn images(&self) -> &[ImageFeature] {
        &self.images
    }

    /// `action`'s names.
    pub fn action_names(&self) -> &[String] {
        &self.action_names
    }

    /// The range of each of `action`'s numbers, lowest first: what a policy may ask.
    pub fn action_ranges(&self) -> &[[f64; 2]] {
        &self.action_ranges
    }

    /// The world's state now, without its images.
    ///
    /// # Errors
    ///
    /// When the world is not simulated.
    pub fn observe_state(&self, world: &World<'_>) -> Result<(Vec<f64>, Vec<f64>), BoxError> {
        let sim = super::sim_backend(world)?;
        let (state, _) = self.sim.joint_values(sim);
        let data = sim.data();
        let environment = self
            .free_joints
            .iter()
            .flat_map(|joint| data.qpos(*joint).to_vec())
            .collect();
        Ok((state, environment))
    }

    /// The world now: state and images.
    ///
    /// # Errors
    ///
    /// When the world is not simulated, or a probe no longer gives an RGB image.
    pub fn observe(&mut self, world: &World<'_>) -> Result<Observation, BoxError> {
        let (state, environment_state) = self.observe_state(world)?;
        let mut images = Vec::with_capacity(self.images.len());
        for image in &self.images {
            let Some(probe) = image.probe else { break };
            match world.probes()[probe].read()? {
                ProbeImage::Rgb { pixels, .. } => images.push(pixels),
                _ => {
                    return Err(format!("{}'s probe no longer gives RGB images", image.key).into());
                }
            }
        }
        images.extend(self.cameras.render(super::sim_backend(world)?)?);
        Ok(Observation {
            state,
            environment_state,
            images,
        })
    }

    /// The action the world follows now: each actuation's targets, then the raw actuators'
    /// controls.
    ///
    /// # Errors
    ///
    /// When the world is not simulated.
    pub fn action(&self, world: &World<'_>) -> Result<Vec<f64>, BoxError> {
        let sim = super::sim_backend(world)?;
        let mut action: Vec<f64> = world
            .actuations()
            .iter()
            .flat_map(|actuation| actuation.target())
            .collect();
        let data = sim.data();
        action.extend(
            self.raw_actuators
                .iter()
                .map(|actuator| data.ctrl()[actuator.index()]),
        );
        Ok(action)
    }

    /// Sets the action: each actuation's share of `action`, then the raw actuators' controls.
    ///
    /// # Errors
    ///
    /// When `action` has not one number per name, or a component refuses its share (naming
    /// it).
    pub fn act(&self, world: &World<'_>, action: &[f64]) -> Result<(), BoxError> {
        if action.len() != self.action_names.len() {
            return Err(format!(
                "the action has {} numbers; this world's has {} ({})",
                action.len(),
                self.action_names.len(),
                self.action_names.join(", ")
            )
            .into());
        }
        let mut rest = action;
        for actuation in world.actuations() {
            let (share, after) = rest.split_at(actuation.names().len());
            actuation.set(share)?;
            rest = after;
        }
        let sim = super::sim_backend(world)?;
        let mut data = sim.data_mut();
        for (actuator, value) in self.raw_actuators.iter().zip(rest) {
            data.set_ctrl(*actuator, *value);
        }
        Ok(())
    }

    /// Puts the free body `name` at `position` with `orientation` (a unit quaternion, w
    /// first): where a task's reset places its objects.
    ///
    /// # Errors
    ///
    /// When the world is not simulated or has no free body `name` (naming those it has).
    pub fn place(
        &self,
        world: &World<'_>,
        name: &str,
        position: [f64; 3],
        orientation: [f64; 4],
    ) -> Result<(), BoxError> {
        let sim = super::sim_backend(world)?;
        let index = self
            .environment_names
            .iter()
            .step_by(POSE_PARTS.len())
            .position(|first| first.strip_suffix("/x") == Some(name))
            .ok_or_else(|| {
                let bodies: Vec<&str> = self
                    .environment_names
                    .iter()
                    .step_by(POSE_PARTS.len())
                    .filter_map(|first| first.strip_suffix("/x"))
                    .collect();
                format!(
                    "no free body {name:?} to place (the free bodies: {})",
                    bodies.join(", ")
                )
            })?;
        let mut data = sim.data_mut();
        let joint = self.free_joints[index];
        let qpos = data.qpos_mut(joint);
        qpos[..3].copy_from_slice(&position);
        qpos[3..].copy_from_slice(&orientation);
        data.qvel_mut(joint).fill(0.0);
        data.kinematics();
        Ok(())
    }
}
