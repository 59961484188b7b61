//! [`McapRecorder`]: a run as an MCAP file — joint states, body poses, images and log lines on
//! the platform's time — that Foxglove, Rerun, ROS 2 tools and the `mcap` libraries open.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::PathBuf;

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_core::runtime::{Plugin, World};
use yarok_mjc::{CameraId, Renderer, SimBackend};

use super::foxglove::{self, Schema};
use super::preset;
use super::sim_state::SimState;
use crate::probe_images;

/// What and how often a [`McapRecorder`] records (`[plugins.mcap]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct McapRecorderSettings {
    /// The MCAP file (created or truncated at start).
    pub path: PathBuf,
    /// Joint states and body poses every this many ticks (`sim` only).
    pub every: u64,
    /// Images a second of platform time, of every probe and camera.
    pub image_hz: f64,
    /// Cameras of the model to record (`sim` only), by name (`overview`, `arm/wrist_cam`);
    /// components' cameras are recorded through their probes anyway.
    pub cameras: Vec<String>,
    /// Width and height of the cameras' images.
    pub size: [u32; 2],
    /// Render with MuJoCo's shadows, reflections and multisampling, several times slower on a
    /// CPU renderer (default: without).
    pub quality: bool,
}

impl Default for McapRecorderSettings {
    fn default() -> Self {
        Self {
            path: PathBuf::from("run.mcap"),
            every: 10,
            image_hz: 10.0,
            cameras: Vec::new(),
            size: [640, 480],
            quality: false,
        }
    }
}

/// The channels of a recording, by what feeds them.
#[derive(Debug, Default)]
struct Channels {
    joint_states: Option<u16>,
    transforms: Option<u16>,
    log: u16,
    /// One per probe, in the world's probe order.
    probes: Vec<u16>,
    /// One per recorded camera.
    cameras: Vec<(CameraId, u16)>,
}

/// Records a run in MCAP: topic `/joint_states` (every joint coordinate's position and
/// velocity, named as [`JointRecorder`](super::JointRecorder) names its columns), `/tf` (every
/// named body's pose in the world frame, `foxglove.FrameTransforms`), one image topic per probe
/// (`/arm/gripper/left/image`: PNG, depth as 16-bit millimetres) and per camera asked for
/// (`/cameras/overview`), and `/log` (the behaviours' [`Pl::log`](yarok_core::runtime::Pl::log)
/// lines, `foxglove.Log`). Messages are JSON; log times are platform time.
///
/// Registered by `yarok::platform()` as `mcap`:
///
/// ```toml
/// [plugins.mcap]
/// path = "pick_and_place.mcap"
/// cameras = ["overview"]
/// ```
pub struct McapRecorder {
    settings: McapRecorderSettings,
    writer: Option<mcap::Writer<BufWriter<File>>>,
    channels: Channels,
    /// In `sim`: the joints and bodies, and the renderer of the cameras asked for.
    sim: Option<SimState>,
    renderer: Option<Renderer>,
    sequence: u32,
    next_image: f64,
}

impl std::fmt::Debug for McapRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("McapRecorder")
            .field("settings", &self.settings)
            .field("messages", &self.sequence)
            .finish()
    }
}

impl McapRecorder {
    /// A recorder with these settings; the file is created when the run starts.
    ///
    /// # Errors
    ///
    /// When `every` is 0 or `image_hz` is not a positive number.
    pub fn new(settings: McapRecorderSettings) -> Result<Self, BoxError> {
        if settings.every == 0 {
            return Err("`every` must be at least 1 tick".into());
        }
        if !(settings.image_hz > 0.0 && settings.image_hz.is_finite()) {
            return Err(format!("`image_hz` {} must be above 0", settings.image_hz).into());
        }
        Ok(Self {
            settings,
            writer: None,
            channels: Channels::default(),
            sim: None,
            renderer: None,
            sequence: 0,
            next_image: 0.0,
        })
    }

    fn failed(&self, error: impl std::fmt::Display) -> BoxError {
        format!("cannot write {}: {error}", self.settings.path.display()).into()
    }

    fn writer(&mut self) -> Result<&mut mcap::Writer<BufWriter<File>>, BoxError> {
        self.writer
            .as_mut()
            .ok_or_else(|| "the recording has not started".into())
    }

    fn channel(&mut self, schema: Schema, topic: &str) -> Result<u16, BoxError> {
        let writer = self.writer()?;
        let added = writer
            .add_schema(schema.name, "jsonschema", schema.json_schema.as_bytes())
            .and_then(|id| writer.add_channel(id, topic, "json", &BTreeMap::new()));
        added.map_err(|e| self.failed(e))
    }

    fn write(
        &mut self,
        channel: u16,
        time: f64,
        message: &serde_json::Value,
    ) -> Result<(), BoxError> {
        let data = serde_json::to_vec(message)?;
        self.sequence += 1;
        let header = mcap::records::MessageHeader {
            channel_id: channel,
            sequence: self.sequence,
            log_time: foxglove::nanoseconds(time),
            publish_time: foxglove::nanoseconds(time),
        };
        let written = self.writer()?.write_to_known_channel(&header, &data);
        written.map_err(|e| self.failed(e))
    }

    /// Finds what `sim` records: joints, bodies and the cameras asked for.
    fn start_sim(&mut self, sim: &SimBackend) -> Result<(), BoxError> {
        let model = sim.model();
        self.sim = Some(SimState::of(sim));
        self.channels.joint_states = Some(self.channel(foxglove::JOINT_STATE, "/joint_states")?);
        self.channels.transforms = Some(self.channel(foxglove::FRAME_TRANSFORMS, "/tf")?);
        if !self.settings.cameras.is_empty() {
            let [width, height] = self.settings.size;
            self.renderer = Some(
                Renderer::builder()
                    .size(width, height)
                    .preset(preset(self.settings.quality))
                    .build(model)?,
            );
        }
        for name in self.settings.cameras.clone() {
            let camera = model
                .camera(&name)
                .map_err(|e| format!("camera {name:?} to record: {e}"))?;
            let channel = self.channel(foxglove::COMPRESSED_IMAGE, &format!("/cameras/{name}"))?;
            self.channels.cameras.push((camera, channel));
        }
        Ok(())
    }

    fn record_sim(&mut self, sim: &SimBackend, time: f64) -> Result<(), BoxError> {
        let (Some(state), Some(joint_states), Some(transforms)) = (
            &self.sim,
            self.channels.joint_states,
            self.channels.transforms,
        ) else {
            return Ok(());
        };
        let (joints, poses) = (state.joint_state(sim, time), state.transforms(sim, time));
        self.write(joint_states, time, &joints)?;
        self.write(transforms, time, &poses)
    }

    fn record_images(&mut self, world: &World<'_>, time: f64) -> Result<(), BoxError> {
        for (probe, channel) in world.probes().iter().zip(self.channels.probes.clone()) {
            let image = probe
                .read()
                .map_err(|e| format!("probe {}/{}: {e}", probe.component(), probe.name()))?;
            let frame = format!("{}/{}", probe.component(), probe.name());
            self.write(
                channel,
                time,
                &foxglove::png_image(time, &frame, &probe_images::png(&image)?),
            )?;
        }
        if let (Some(sim), Some(renderer)) = (world.backend::<SimBackend>(), &mut self.renderer) {
            let mut images = Vec::with_capacity(self.channels.cameras.len());
            for (camera, channel) in &self.channels.cameras {
                let rgb = renderer.render_rgb(&mut sim.data_mut(), *camera)?;
                let (width, height) = rgb.dimensions();
                let image = ProbeImage::Rgb {
                    width,
                    height,
                    pixels: rgb.into_raw(),
                };
                images.push((*channel, probe_images::png(&image)?));
            }
            for ((channel, png), name) in images.into_iter().zip(self.settings.cameras.clone()) {
                self.write(channel, time, &foxglove::png_image(time, &name, &png))?;
            }
        }
        Ok(())
    }

    fn record_log(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let lines: Vec<_> = world.log().to_vec();
        for line in lines {
            self.write(
                self.channels.log,
                line.time,
                &foxglove::log(line.time, &line.text),
            )?;
        }
        Ok(())
    }
}

impl Plugin for McapRecorder {
    fn name(&self) -> String {
        format!("mcap ({})", self.settings.path.display())
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let path = &self.settings.path;
        let file =
            File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
        let options = mcap::WriteOptions::new()
            .compression(None)
            .library(concat!("yarok ", env!("CARGO_PKG_VERSION")));
        let writer = options
            .create(BufWriter::new(file))
            .map_err(|e| self.failed(e))?;
        self.writer = Some(writer);
        self.channels.log = self.channel(foxglove::LOG, "/log")?;
        for probe in world.probes() {
            let topic = format!("{}/{}", probe.component(), probe.name());
            let channel = self.channel(foxglove::COMPRESSED_IMAGE, &topic)?;
            self.channels.probes.push(channel);
        }
        match world.backend::<SimBackend>() {
            Some(sim) => self.start_sim(sim),
            None if self.settings.cameras.is_empty() => Ok(()),
            None => Err(format!(
                "records the model's cameras in `sim`, not in `{}`",
                world.pl().environment()
            )
            .into()),
        }
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        // The platform steps plugins before it counts the tick and advances its clock.
        let tick = world.pl().ticks() + 1;
        let sim = world.backend::<SimBackend>();
        let time = sim.map_or(world.pl().time(), |sim| sim.data().time());
        if let Some(sim) = sim
            && tick.is_multiple_of(self.settings.every)
        {
            self.record_sim(sim, time)?;
        }
        if time + 1e-9 >= self.next_image {
            self.next_image += 1.0 / self.settings.image_hz;
            self.record_images(world, time)?;
        }
        self.record_log(world)
    }

    fn end(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        if self.writer.is_none() {
            return Ok(());
        }
        self.record_log(world)?;
        let mut writer = self.writer.take().ok_or("the recording has not started")?;
        writer.finish().map_err(|e| self.failed(e))?;
        let mut file = writer.into_inner();
        std::io::Write::flush(&mut file).map_err(|e| self.failed(e))
    }
}
