//! [`Features`]: a world's observation and action as a policy sees them and a LeRobot dataset
//! records them (the plugins record and show them) — `observation.state`,
//! `observation.environment_state`, `observation.images.*` and `action` — with the same names
//! and shapes everywhere, in `sim` and on hardware.

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_core::runtime::World;
use yarok_mjc::{ActuatorId, JointId, SimBackend};

use crate::model_cameras::ModelCameras;

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

/// A world's features, found once when it starts, in any environment:
/// - `observation.state`: where each component's actuators are ([`World::actuations`]'
///   measures: an arm's joint positions, a gripper's position), named as its action; in `sim`,
///   then the position of every hinge and slide of the model outside the actuated components,
///   named as in the model;
/// - `observation.environment_state`: in `sim`, every free body's pose ([`POSE_PARTS`] each,
///   named `medium/block/x` … `medium/block/qz`): where the objects are. On hardware nothing
///   measures them: empty;
/// - `observation.images.{probe}`: every RGB probe's image (`observation.images.arm.gripper.left_digit.image`),
///   then, in `sim`, `observation.images.{camera}` for each camera of the model asked for
///   (`observation.images.overview`);
/// - `action`: every component's actuation (an arm's joint targets, a gripper's position), then
///   in `sim` the raw control of every actuator no actuation drives.
///
/// So a policy trained on a `sim` world's dataset observes and drives the real world through
/// the same names, as far as the real world can measure them.
#[derive(Debug)]
pub struct Features {
    state_names: Vec<String>,
    /// The model's hinges and slides outside the actuated components (`sim`).
    joints: Vec<JointId>,
    free_joints: Vec<JointId>,
    environment_names: Vec<String>,
    images: Vec<ImageFeature>,
    cameras: ModelCameras,
    action_names: Vec<String>,
    action_ranges: Vec<[f64; 2]>,
    /// The actuators driven by their control input directly (`sim`).
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

/// Whether `action` has one number per name of a world's `action_names`; else what it should
/// have, in words.
///
/// # Errors
///
/// When the counts differ, naming the action's numbers.
pub fn check_action_length(action_names: &[String], action: &[f64]) -> Result<(), String> {
    if action.len() == action_names.len() {
        return Ok(());
    }
    Err(format!(
        "the action has {} numbers; this world's has {} ({})",
        action.len(),
        action_names.len(),
        action_names.join(", ")
    ))
}

impl Features {
    /// The features of `world`, a world that has started, with the model's `cameras` rendered
    /// at `size` (with MuJoCo's shadows and reflections when `quality`).
    ///
    /// # Errors
    ///
    /// When a probe cannot be read, cameras are asked for outside `sim`, the model has no
    /// camera of a name, or the renderer cannot be made.
    pub fn of(
        world: &World<'_>,
        cameras: &[String],
        size: [u32; 2],
        quality: bool,
    ) -> Result<Self, BoxError> {
        let actuations = world.actuations();
        let mut state_names: Vec<String> = actuations
            .iter()
            .flat_map(|actuation| actuation.names().iter().cloned())
            .collect();
        let mut action_names = state_names.clone();
        let mut action_ranges: Vec<[f64; 2]> = actuations
            .iter()
            .flat_map(|actuation| actuation.ranges().iter().copied())
            .collect();
        let actuated: Vec<String> = actuations
            .iter()
            .map(|actuation| format!("{}/", actuation.component().trim_start_matches('/')))
            .collect();
        let is_actuated = |name: &str| actuated.iter().any(|prefix| name.starts_with(prefix));
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
        let mut features = Self {
            state_names: Vec::new(),
            joints: Vec::new(),
            free_joints: Vec::new(),
            environment_names: Vec::new(),
            images,
            cameras: ModelCameras::default(),
            action_names: Vec::new(),
            action_ranges: Vec::new(),
            raw_actuators: Vec::new(),
        };
        let Some(sim) = world.backend::<SimBackend>() else {
            if let Some(camera) = cameras.first() {
                return Err(format!(
                    "the model's camera {camera:?} is rendered only in `sim`; in `{}` a camera \
                     is a component with a probe",
                    world.pl().environment()
                )
                .into());
            }
            features.state_names = state_names;
            features.action_names = action_names;
            features.action_ranges = action_ranges;
            return Ok(features);
        };
        let model = sim.model();
        let data = sim.data();
        for (index, joint) in model.joints().enumerate() {
            let body = || {
                model
                    .body_name(model.joint_body(joint))
                    .unwrap_or_else(|| format!("body{index}"))
            };
            match data.qpos(joint).len() {
                1 => {
                    let name = model
                        .joint_name(joint)
                        .unwrap_or_else(|| format!("{}/joint", body()));
                    if !is_actuated(&name) {
                        features.joints.push(joint);
                        state_names.push(name);
                    }
                }
                7 => {
                    let body = body();
                    features.free_joints.push(joint);
                    features
                        .environment_names
                        .extend(POSE_PARTS.iter().map(|part| format!("{body}/{part}")));
                }
                _ => {}
            }
        }
        drop(data);
        for (index, actuator) in model.actuators().enumerate() {
            let name = model
                .actuator_name(actuator)
                .unwrap_or_else(|| format!("actuator{index}"));
            if !is_actuated(&name) {
                features.raw_actuators.push(actuator);
                action_names.push(name);
                let unbounded = [f64::NEG_INFINITY, f64::INFINITY];
                action_ranges.push(model.ctrl_range(actuator).unwrap_or(unbounded));
            }
        }
        features
            .images
            .extend(cameras.iter().map(|camera| ImageFeature {
                key: image_key(camera),
                size,
                probe: None,
            }));
        features.cameras = ModelCameras::find(sim, cameras, size, quality)?;
        features.state_names = state_names;
        features.action_names = action_names;
        features.action_ranges = action_ranges;
        Ok(features)
    }

    /// `observation.state`'s names: the actuators', then (`sim`) the other joints'.
    pub fn state_names(&self) -> &[String] {
        &self.state_names
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

    /// The world's state now, without its images: `observation.state` and
    /// `observation.environment_state`.
    pub fn observe_state(&self, world: &World<'_>) -> (Vec<f64>, Vec<f64>) {
        let mut state: Vec<f64> = world
            .actuations()
            .iter()
            .flat_map(|actuation| actuation.measured())
            .collect();
        let Some(sim) = world.backend::<SimBackend>() else {
            return (state, Vec::new());
        };
        let data = sim.data();
        state.extend(self.joints.iter().map(|joint| data.qpos(*joint)[0]));
        let environment = self
            .free_joints
            .iter()
            .flat_map(|joint| data.qpos(*joint).to_vec())
            .collect();
        (state, environment)
    }

    /// The world now: state and images.
    ///
    /// # Errors
    ///
    /// When a probe no longer gives an RGB image, or a camera cannot be rendered.
    pub fn observe(&mut self, world: &World<'_>) -> Result<Observation, BoxError> {
        let (state, environment_state) = self.observe_state(world);
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
        if let Some(sim) = world.backend::<SimBackend>() {
            images.extend(self.cameras.render(sim)?);
        }
        Ok(Observation {
            state,
            environment_state,
            images,
        })
    }

    /// The action that takes the world from now to `ahead` seconds on as it is going: each
    /// actuation's targets `ahead` seconds from now ([`NamedActuation::target`]: a streamed
    /// target, where a motion is due then), then (`sim`) the raw actuators' controls. A
    /// dataset's `action` of a frame, `ahead` its period: given to [`Features::act`] at the
    /// frame, it leads to the next frame's state, as the command of a leader arm leads its
    /// follower in LeRobot's datasets.
    ///
    /// [`NamedActuation::target`]: yarok_core::component::NamedActuation::target
    pub fn action(&self, world: &World<'_>, ahead: f64) -> Vec<f64> {
        let mut action: Vec<f64> = world
            .actuations()
            .iter()
            .flat_map(|actuation| actuation.target(ahead))
            .collect();
        if let Some(sim) = world.backend::<SimBackend>() {
            let data = sim.data();
            action.extend(
                self.raw_actuators
                    .iter()
                    .map(|actuator| data.ctrl()[actuator.index()]),
            );
        }
        action
    }

    /// Sets the action: each actuation's share of `action`, then the raw actuators' controls.
    /// Every share is checked against its names and ranges before any is set, so that an
    /// action refused for one component changes none.
    ///
    /// # Errors
    ///
    /// When `action` has not one number per name, or a component refuses its share (naming
    /// it).
    pub fn act(&self, world: &World<'_>, action: &[f64]) -> Result<(), BoxError> {
        check_action_length(&self.action_names, action)?;
        let actuations = world.actuations();
        let mut shares = Vec::with_capacity(actuations.len());
        let mut rest = action;
        for actuation in actuations {
            let (share, after) = rest.split_at(actuation.names().len());
            actuation.check(share)?;
            shares.push(share);
            rest = after;
        }
        for (actuation, share) in actuations.iter().zip(shares) {
            actuation.set(share)?;
        }
        if let Some(sim) = world.backend::<SimBackend>() {
            let mut data = sim.data_mut();
            for (actuator, value) in self.raw_actuators.iter().zip(rest) {
                data.set_ctrl(*actuator, *value);
            }
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
        let sim: &SimBackend = world.backend().ok_or_else(|| {
            format!(
                "cannot place {name:?}: the world runs in `{}`, not simulated",
                world.pl().environment()
            )
        })?;
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
