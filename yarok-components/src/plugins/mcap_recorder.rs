//! [`McapRecorder`]: a run as an MCAP file — joint states, body poses, images and log lines on
//! the platform's time — that Foxglove, Rerun, ROS 2 tools and the `mcap` libraries open.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_core::runtime::{Episode, Happening, LogLine, Plugin, World};
use yarok_mjc::{CameraId, Renderer, SimBackend};

use super::foxglove;
use super::preset;
use super::recording_profile::{self, MessageKind, RecordingProfile};
use super::sim_state::SimState;
use crate::probe_images;

/// What and how often a [`McapRecorder`] records (`[plugins.mcap]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct McapRecorderSettings {
    /// The MCAP file (created, with its folder, or truncated at start).
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
    /// How messages are encoded: `"json"` (the default: Foxglove's JSON shapes) or `"ros2"`
    /// (CDR-encoded ROS 2 messages that `ros2 bag` plays).
    pub profile: String,
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
            profile: "json".to_owned(),
        }
    }
}

/// The channels of a recording, by what feeds them.
#[derive(Debug, Default)]
struct Channels {
    joint_states: Option<u16>,
    transforms: Option<u16>,
    clock: Option<u16>,
    log: u16,
    /// One per probe, in the world's probe order.
    probes: Vec<u16>,
    /// One per recorded camera, in the settings' order.
    cameras: Vec<u16>,
}

/// One MCAP file: the run's, or an episode's, whose times count from the episode's start.
struct Recording {
    path: PathBuf,
    profile: Arc<dyn RecordingProfile>,
    writer: mcap::Writer<BufWriter<File>>,
    channels: Channels,
    episode: Option<Episode>,
    sequence: u32,
    next_image: f64,
}

impl Recording {
    /// Creates `path` with a channel for every probe, and in `sim` for the joints, the bodies
    /// and `cameras`.
    fn create(
        path: PathBuf,
        profile: &Arc<dyn RecordingProfile>,
        world: &World<'_>,
        cameras: &[(String, CameraId)],
        episode: Option<Episode>,
    ) -> Result<Self, BoxError> {
        let cannot = |e: std::io::Error| format!("cannot create {}: {e}", path.display());
        if let Some(folder) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(folder).map_err(cannot)?;
        }
        let file = File::create(&path).map_err(cannot)?;
        let options = mcap::WriteOptions::new()
            .compression(None)
            .profile(profile.mcap_profile())
            .library(concat!("yarok ", env!("CARGO_PKG_VERSION")));
        let mut writer = options
            .create(BufWriter::new(file))
            .map_err(|e| failed(&path, e))?;
        writer
            .write_metadata(&run_metadata(world, episode)?)
            .map_err(|e| failed(&path, e))?;
        let mut recording = Self {
            path,
            profile: Arc::clone(profile),
            writer,
            channels: Channels::default(),
            episode,
            sequence: 0,
            next_image: 0.0,
        };
        recording.channels.log = recording.channel(MessageKind::Log, "/log")?;
        for probe in world.probes() {
            // A depth probe's channel states the unit its PNGs count in (as their text does).
            let mut metadata = BTreeMap::new();
            let mut kind = MessageKind::Image;
            if let Ok(ProbeImage::Depth { unit, .. }) = probe.read() {
                metadata.insert(
                    probe_images::DEPTH_UNIT_KEYWORD.to_owned(),
                    format!("{unit:e}"),
                );
                kind = MessageKind::Depth;
            }
            let channel = recording.channel_with(kind, &probe.path(), &metadata)?;
            recording.channels.probes.push(channel);
        }
        if world.backend::<SimBackend>().is_some() {
            recording.channels.joint_states =
                Some(recording.channel(MessageKind::JointState, "/joint_states")?);
            recording.channels.transforms =
                Some(recording.channel(MessageKind::Transforms, "/tf")?);
        }
        if recording.profile.schema(MessageKind::Clock).is_some() {
            recording.channels.clock = Some(recording.channel(MessageKind::Clock, "/clock")?);
        }
        for (name, _) in cameras {
            let channel = recording.channel(MessageKind::Image, &format!("/cameras/{name}"))?;
            recording.channels.cameras.push(channel);
        }
        Ok(recording)
    }

    fn channel(&mut self, kind: MessageKind, topic: &str) -> Result<u16, BoxError> {
        self.channel_with(kind, topic, &BTreeMap::new())
    }

    fn channel_with(
        &mut self,
        kind: MessageKind,
        topic: &str,
        metadata: &BTreeMap<String, String>,
    ) -> Result<u16, BoxError> {
        let schema = self
            .profile
            .schema(kind)
            .ok_or_else(|| format!("the recording's profile has no {kind:?} messages"))?;
        let encoding = self.profile.message_encoding();
        let writer = &mut self.writer;
        let added = writer
            .add_schema(schema.name, schema.encoding, schema.data.as_bytes())
            .and_then(|id| writer.add_channel(id, topic, encoding, metadata));
        added.map_err(|e| failed(&self.path, e))
    }

    fn write(&mut self, channel: u16, time: f64, data: &[u8]) -> Result<(), BoxError> {
        self.sequence += 1;
        let header = mcap::records::MessageHeader {
            channel_id: channel,
            sequence: self.sequence,
            log_time: foxglove::nanoseconds(time),
            publish_time: foxglove::nanoseconds(time),
        };
        let written = self.writer.write_to_known_channel(&header, data);
        written.map_err(|e| failed(&self.path, e))
    }

    /// The time a recording of platform tick `tick` (at platform time `time`) reads.
    fn time(&self, tick: u64, time: f64, timestep: f64) -> f64 {
        self.episode
            .map_or(time, |episode| episode.time_at(tick, timestep))
    }

    /// Ticks since the recording began.
    fn ticks(&self, tick: u64) -> u64 {
        self.episode
            .map_or(tick, |episode| tick.saturating_sub(episode.start_tick))
    }

    fn write_log(&mut self, line: &LogLine, timestep: f64) -> Result<(), BoxError> {
        let time = self.time(line.tick, line.time, timestep);
        let message = self.profile.log(time, &line.text);
        self.write(self.channels.log, time, &message)
    }

    fn finish(mut self) -> Result<(), BoxError> {
        self.writer.finish().map_err(|e| failed(&self.path, e))?;
        let mut file = self.writer.into_inner();
        std::io::Write::flush(&mut file).map_err(|e| failed(&self.path, e))
    }
}

/// The run a recording is of, as its `yarok` metadata record states it: the world's tag, the
/// environment, the platform's seed and timestep, yarok's version, and the episode's number
/// (an episode's file) or the shard (the run's: an episode's file is the same whichever shard
/// recorded it).
fn run_metadata(
    world: &World<'_>,
    episode: Option<Episode>,
) -> Result<mcap::records::Metadata, BoxError> {
    let pl = world.pl();
    let platform = world.settings().platform_settings()?;
    let mut metadata = BTreeMap::from([
        (
            "world".to_owned(),
            world.composition().instances[0].tag.clone(),
        ),
        ("environment".to_owned(), pl.environment().to_owned()),
        ("seed".to_owned(), platform.seed.to_string()),
        ("timestep".to_owned(), pl.timestep().to_string()),
        ("yarok".to_owned(), env!("CARGO_PKG_VERSION").to_owned()),
    ]);
    let (key, value) = match episode {
        Some(episode) => ("episode", episode.number.to_string()),
        None => {
            let shard = pl.shard();
            ("shard", format!("{}/{}", shard.index, shard.count))
        }
    };
    metadata.insert(key.to_owned(), value);
    Ok(mcap::records::Metadata {
        name: "yarok".to_owned(),
        metadata,
    })
}

fn failed(path: &Path, error: impl std::fmt::Display) -> BoxError {
    format!("cannot write {}: {error}", path.display()).into()
}

/// Records a run in MCAP: topic `/joint_states` (every joint coordinate's position and
/// velocity, named as [`JointRecorder`](super::JointRecorder) names its columns), `/tf` (every
/// named body's pose in the world frame, `foxglove.FrameTransforms`), one image topic per probe
/// (`/arm/gripper/left/image`: PNG; depth as 16-bit counts of the unit its channel's metadata and
/// the PNG's text state under `depth_unit_m` — a tactile sensor's 1 µm, a camera's 1 mm; see
/// [`probe_images::png`](crate::probe_images::png)) and per camera asked for
/// (`/cameras/overview`), and `/log` (the behaviours' [`Pl::log`](yarok_core::runtime::Pl::log)
/// lines, `foxglove.Log`). Messages are JSON; times are platform time.
///
/// Each episode a behaviour begins ([`Pl::begin_episode`](yarok_core::runtime::Pl::begin_episode))
/// is recorded in a file of its own beside `path` — `run_episode_0007.mcap` for episode 7 of
/// `run.mcap` — whose times count from the episode's start, so that an episode's file is the
/// same, byte for byte, whichever episodes ran before it. What happens outside episodes goes to
/// `path`, which a sharded run (`[platform] shard = "1/3"`) names `run_1_of_3.mcap`.
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
    profile: Arc<dyn RecordingProfile>,
    /// The run's file, and the current episode's.
    run: Option<Recording>,
    episode: Option<Recording>,
    /// In `sim`: the joints and bodies, and the renderer of the cameras asked for.
    sim: Option<SimState>,
    renderer: Option<Renderer>,
    cameras: Vec<(String, CameraId)>,
}

impl std::fmt::Debug for McapRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("McapRecorder")
            .field("settings", &self.settings)
            .field("episode", &self.episode.as_ref().and_then(|r| r.episode))
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
        let profile =
            recording_profile::named(&settings.profile).map_err(|e| format!("`profile`: {e}"))?;
        Ok(Self {
            profile: Arc::from(profile),
            settings,
            run: None,
            episode: None,
            sim: None,
            renderer: None,
            cameras: Vec::new(),
        })
    }

    /// `path` with `suffix` added to its file name, before the extension.
    fn beside(&self, suffix: &str) -> PathBuf {
        let path = &self.settings.path;
        let stem = path.file_stem().unwrap_or_default().to_string_lossy();
        let extension = path
            .extension()
            .map_or("mcap".into(), |e| e.to_string_lossy());
        path.with_file_name(format!("{stem}{suffix}.{extension}"))
    }

    /// Finds what `sim` records: joints, bodies and the cameras asked for.
    fn start_sim(&mut self, sim: &SimBackend) -> Result<(), BoxError> {
        let model = sim.model();
        self.sim = Some(SimState::of(sim));
        if !self.settings.cameras.is_empty() {
            let [width, height] = self.settings.size;
            self.renderer = Some(
                Renderer::builder()
                    .size(width, height)
                    .preset(preset(self.settings.quality))
                    .build(model)?,
            );
        }
        for name in &self.settings.cameras {
            let camera = model
                .camera(name)
                .map_err(|e| format!("camera {name:?} to record: {e}"))?;
            self.cameras.push((name.clone(), camera));
        }
        Ok(())
    }

    /// The file being recorded into: the episode's, or the run's.
    fn recording(&mut self) -> Result<&mut Recording, BoxError> {
        self.episode
            .as_mut()
            .or(self.run.as_mut())
            .ok_or_else(|| "the recording has not started".into())
    }

    /// Writes the lines logged since the last step into the files they belong to, opening and
    /// closing episodes' files as they began and ended among them.
    fn follow_episodes(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let timestep = world.pl().timestep();
        for happening in world.happenings().iter() {
            match happening {
                Happening::Logged(line) => self.recording()?.write_log(line, timestep)?,
                Happening::EpisodeBegan(episode) => {
                    let path = self.beside(&format!("_episode_{:04}", episode.number));
                    let recording = Recording::create(
                        path,
                        &self.profile,
                        world,
                        &self.cameras,
                        Some(*episode),
                    )?;
                    self.episode = Some(recording);
                }
                Happening::EpisodeEnded(_) => {
                    if let Some(ended) = self.episode.take() {
                        ended.finish()?;
                    }
                }
            }
        }
        Ok(())
    }

    fn record_sim(&mut self, sim: &SimBackend, time: f64) -> Result<(), BoxError> {
        let Some(state) = &self.sim else {
            return Ok(());
        };
        let (joints, poses) = (
            self.profile.joint_state(time, &state.joint_values(sim)),
            self.profile.transforms(time, &state.poses(sim)),
        );
        let recording = self.recording()?;
        let (Some(joint_states), Some(transforms)) = (
            recording.channels.joint_states,
            recording.channels.transforms,
        ) else {
            return Ok(());
        };
        recording.write(joint_states, time, &joints)?;
        recording.write(transforms, time, &poses)
    }

    fn record_clock(&mut self, time: f64) -> Result<(), BoxError> {
        let recording = self.recording()?;
        if let (Some(channel), Some(message)) =
            (recording.channels.clock, recording.profile.clock(time))
        {
            recording.write(channel, time, &message)?;
        }
        Ok(())
    }

    fn record_images(&mut self, world: &World<'_>, time: f64) -> Result<(), BoxError> {
        let mut images = Vec::new();
        for probe in world.probes() {
            let image = probe.read()?;
            images.push(self.profile.image(time, &probe.path(), &image)?);
        }
        if let (Some(sim), Some(renderer)) = (world.backend::<SimBackend>(), &mut self.renderer) {
            for (name, camera) in &self.cameras {
                let rgb = renderer.render_rgb(&mut sim.data_mut(), *camera)?;
                let (width, height) = rgb.dimensions();
                let image = ProbeImage::Rgb {
                    width,
                    height,
                    pixels: rgb.into_raw(),
                };
                images.push(self.profile.image(time, name, &image)?);
            }
        }
        let recording = self.recording()?;
        let channels: Vec<u16> = recording
            .channels
            .probes
            .iter()
            .chain(&recording.channels.cameras)
            .copied()
            .collect();
        for (channel, message) in channels.into_iter().zip(images) {
            recording.write(channel, time, &message)?;
        }
        Ok(())
    }
}

impl Plugin for McapRecorder {
    fn writes(&self) -> Vec<std::path::PathBuf> {
        vec![self.settings.path.clone()]
    }

    fn name(&self) -> String {
        format!("mcap ({})", self.settings.path.display())
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        match world.backend::<SimBackend>() {
            Some(sim) => self.start_sim(sim)?,
            None if self.settings.cameras.is_empty() => {}
            None => {
                return Err(format!(
                    "records the model's cameras in `sim`, not in `{}`",
                    world.pl().environment()
                )
                .into());
            }
        }
        let shard = world.pl().shard();
        let path = if shard.is_whole() {
            self.settings.path.clone()
        } else {
            self.beside(&format!("_{}_of_{}", shard.index, shard.count))
        };
        self.run = Some(Recording::create(
            path,
            &self.profile,
            world,
            &self.cameras,
            None,
        )?);
        Ok(())
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.follow_episodes(world)?;
        // The platform steps plugins before it counts the tick and advances its clock.
        let tick = world.pl().ticks() + 1;
        let sim = world.backend::<SimBackend>();
        let now = sim.map_or(world.pl().time(), |sim| sim.data().time());
        let (every, image_period) = (self.settings.every, 1.0 / self.settings.image_hz);
        let recording = self.recording()?;
        let time = recording.time(tick, now, world.pl().timestep());
        let record_state = recording.ticks(tick).is_multiple_of(every);
        let record_images = time + 1e-9 >= recording.next_image;
        if record_images {
            // Back in the run's file after an episode, the schedule resumes from now.
            recording.next_image = (recording.next_image + image_period).max(time);
        }
        if record_state {
            self.record_clock(time)?;
            if let Some(sim) = sim {
                self.record_sim(sim, time)?;
            }
        }
        if record_images {
            self.record_images(world, time)?;
        }
        Ok(())
    }

    fn end(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        if self.run.is_none() {
            return Ok(());
        }
        self.follow_episodes(world)?;
        if let Some(episode) = self.episode.take() {
            episode.finish()?;
        }
        self.run
            .take()
            .ok_or("the recording has not started")?
            .finish()
    }
}
