//! [`McapRecorder`]: a run as an MCAP file — joint states, transform frames, components' named
//! states, images and log lines on the platform's time — that Foxglove, Rerun, ROS 2 tools and the `mcap` libraries
//! open.

mod file;
mod writer;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_core::runtime::{Episode, Happening, Plugin, World};
use yarok_mjc::SimBackend;

use self::file::{ImageChannel, Layout, McapFile, SimNames, SimSample};
use self::writer::{Job, Writer};
use super::recording_profile::{self, MessageKind, RecordingProfile};
use super::sim_state::{SimState, optical_frame};
use crate::model_cameras::ModelCameras;
use crate::probe_images;

/// What and how often a [`McapRecorder`] records (`[plugins.mcap]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct McapRecorderSettings {
    /// The MCAP file (created, with its folder, at start; a file there is replaced only if
    /// yarok recorded it).
    pub path: PathBuf,
    /// Joint states and body poses (`sim` only) and components' named states every this many
    /// ticks.
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
    /// How messages are encoded: `"foxglove"` (the default: JSON in Foxglove's well-known
    /// shapes, with self-contained JSON Schemas) or `"ros2"` (CDR-encoded ROS 2 messages with
    /// their `ros2msg` definitions, that `ros2 bag` plays).
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
            profile: "foxglove".to_owned(),
        }
    }
}

/// Where a file's times and image schedule stand: the run's, or an episode's, whose times count
/// from the episode's start.
#[derive(Debug, Clone, Copy, Default)]
struct FileClock {
    episode: Option<Episode>,
    next_image: f64,
}

impl FileClock {
    /// The time a recording of platform tick `tick` (at platform time `time`) reads.
    fn time(&self, tick: u64, time: f64, timestep: f64) -> f64 {
        self.episode
            .map_or(time, |episode| episode.time_at(tick, timestep))
    }

    /// Ticks since the file began.
    fn ticks(&self, tick: u64) -> u64 {
        self.episode
            .map_or(tick, |episode| tick.saturating_sub(episode.start_tick))
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

/// Records a run in MCAP: topic `/joint_states` (every hinge's and slide's position and
/// velocity, `foxglove.JointStates`), `/tf` (`foxglove.FrameTransforms`: every named body's
/// pose in the world frame, and every named camera's optical frame, `{camera}/optical`), one
/// image topic per probe (`/arm/gripper/left/image`: PNG in its camera's optical frame; depth as
/// a `foxglove.RawImage` of 16-bit `16UC1` counts of the unit its channel's metadata states
/// under `depth_unit_m` — a tactile sensor's 1 µm, a camera's 1 mm) and per camera asked for
/// (`/cameras/overview`), one topic per component's
/// [named state](yarok_core::component::NamedState) (`/arm/state`, `yarok.State`: its fields
/// and a `timestamp`, every `every` ticks in any environment), and `/log` (the behaviours' [`Pl::log`](yarok_core::runtime::Pl::log)
/// lines, `foxglove.Log`). Times are platform time; every file starts with a `yarok` metadata
/// record (world, environment, seed, timestep, yarok's version, shard or episode); chunks are
/// zstd-compressed. The `ros2` profile writes the same as ROS 2 messages (a state as its JSON
/// in a `std_msgs/msg/String`), with `/clock`.
///
/// What the platform's thread does is take the state and images; a thread of the recorder's
/// own encodes and writes them, its queue bounded (a writer that takes nothing for 10 s ends
/// the run with an error).
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
    layout: Layout,
    writer: Option<Writer>,
    /// The run's file's clock, and the current episode's.
    run: FileClock,
    episode: Option<FileClock>,
    /// In `sim`: the joints and frames, and the cameras asked for.
    sim: Option<SimState>,
    cameras: ModelCameras,
}

impl std::fmt::Debug for McapRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("McapRecorder")
            .field("settings", &self.settings)
            .field("episode", &self.episode.and_then(|clock| clock.episode))
            .finish()
    }
}

impl McapRecorder {
    /// A recorder with these settings; the file is created when the run starts.
    ///
    /// # Errors
    ///
    /// When `every` is 0, `image_hz` is not a positive number or there is no such `profile`.
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
            layout: Layout::default(),
            writer: None,
            run: FileClock::default(),
            episode: None,
            sim: None,
            cameras: ModelCameras::default(),
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

    /// Finds what `sim` records: joints, frames and the cameras asked for.
    fn start_sim(&mut self, sim: &SimBackend) -> Result<(), BoxError> {
        let state = SimState::of(sim);
        self.layout.sim = Some(SimNames {
            joints: state.joint_names().into(),
            frames: state.frame_names().into(),
        });
        self.sim = Some(state);
        let settings = &self.settings;
        self.cameras = ModelCameras::find(sim, &settings.cameras, settings.size, settings.quality)?;
        Ok(())
    }

    /// An image channel for every probe, then every camera asked for.
    fn image_channels(&self, world: &World<'_>) -> Vec<ImageChannel> {
        let mut channels = Vec::new();
        for probe in world.probes() {
            // A depth probe's channel states the unit its images count in (a PNG's, as its text
            // does; metres for ROS 2's 32FC1).
            let mut metadata = BTreeMap::new();
            let mut kind = MessageKind::Image;
            if let Ok(ProbeImage::Depth { unit, .. }) = probe.read() {
                metadata.insert(
                    probe_images::DEPTH_UNIT_KEYWORD.to_owned(),
                    format!("{:e}", self.profile.depth_unit_m(unit)),
                );
                kind = MessageKind::Depth;
            }
            let frame = self.sim.as_ref().map_or_else(
                || "world".to_owned(),
                |sim| sim.frame_of_component(probe.component()),
            );
            channels.push(ImageChannel {
                topic: probe.path(),
                kind,
                metadata,
                frame,
            });
        }
        for name in self.cameras.names() {
            channels.push(ImageChannel {
                topic: format!("/cameras/{name}"),
                kind: MessageKind::Image,
                metadata: BTreeMap::new(),
                frame: optical_frame(name),
            });
        }
        channels
    }

    fn writer(&mut self) -> Result<&mut Writer, BoxError> {
        self.writer
            .as_mut()
            .ok_or_else(|| "the recording has not started".into())
    }

    /// The clock of the file being recorded into: the episode's, or the run's.
    fn clock(&mut self) -> &mut FileClock {
        self.episode.as_mut().unwrap_or(&mut self.run)
    }

    /// Hands over the lines logged since the last step, and the episodes that began and ended
    /// among them: an episode's file is created here, so that an error names it at once, and
    /// is complete on disk once the episode has ended.
    fn follow_episodes(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let timestep = world.pl().timestep();
        for happening in world.happenings().iter() {
            match happening {
                Happening::Logged(line) => {
                    let time = self.clock().time(line.tick, line.time, timestep);
                    let text = line.text.clone();
                    self.writer()?.send(Job::Log { time, text })?;
                }
                Happening::EpisodeBegan(episode) => {
                    self.end_episode()?;
                    let path = self.beside(&format!("_episode_{:04}", episode.number));
                    let metadata = run_metadata(world, Some(*episode))?;
                    let file = McapFile::create(path, &self.profile, &self.layout, &metadata)?;
                    self.episode = Some(FileClock {
                        episode: Some(*episode),
                        next_image: 0.0,
                    });
                    self.writer()?.send(Job::BeginEpisode(Box::new(file)))?;
                }
                Happening::EpisodeEnded(_) => self.end_episode()?,
                Happening::TaskSet(_) => {}
            }
        }
        Ok(())
    }

    /// Closes the episode's file, if one is open.
    fn end_episode(&mut self) -> Result<(), BoxError> {
        if self.episode.take().is_some() {
            self.writer()?.end_episode()?;
        }
        Ok(())
    }

    fn images(&mut self, world: &World<'_>) -> Result<Vec<ProbeImage>, BoxError> {
        let mut images = Vec::new();
        for probe in world.probes() {
            images.push(probe.read()?);
        }
        if let Some(sim) = world.backend::<SimBackend>() {
            let [width, height] = self.settings.size;
            for pixels in self.cameras.render(sim)? {
                images.push(ProbeImage::Rgb {
                    width,
                    height,
                    pixels,
                });
            }
        }
        Ok(images)
    }
}

impl Plugin for McapRecorder {
    fn writes(&self) -> Vec<std::path::PathBuf> {
        vec![self.settings.path.clone()]
    }

    fn name(&self) -> String {
        format!("mcap ({})", self.settings.path.display())
    }

    /// Any, unless it records the model's cameras, which only `sim` has.
    fn environments(&self) -> Vec<&'static str> {
        if self.settings.cameras.is_empty() {
            Vec::new()
        } else {
            crate::plugins::only_sim()
        }
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        if let Some(sim) = world.backend::<SimBackend>() {
            self.start_sim(sim)?;
        }
        self.layout.images = self.image_channels(world);
        self.layout.states = world.states().iter().map(|state| state.path()).collect();
        let shard = world.pl().shard();
        let path = if shard.is_whole() {
            self.settings.path.clone()
        } else {
            self.beside(&format!("_{}_of_{}", shard.index, shard.count))
        };
        let metadata = run_metadata(world, None)?;
        let run = McapFile::create(path, &self.profile, &self.layout, &metadata)?;
        self.writer = Some(Writer::start(run)?);
        Ok(())
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.follow_episodes(world)?;
        let tick = world.pl().ticks();
        let sim = world.backend::<SimBackend>();
        let now = sim.map_or(world.pl().time(), |sim| sim.data().time());
        let (every, image_period) = (self.settings.every, 1.0 / self.settings.image_hz);
        let clock = self.clock();
        let time = clock.time(tick, now, world.pl().timestep());
        let record_state = clock.ticks(tick).is_multiple_of(every);
        let record_images = time + 1e-9 >= clock.next_image;
        if record_images {
            // Back in the run's file after an episode, the schedule resumes from now.
            clock.next_image = (clock.next_image + image_period).max(time);
        }
        if record_state {
            let sim = match (sim, &self.sim) {
                (Some(sim), Some(state)) => {
                    let (positions, velocities) = state.joint_values(sim);
                    Some(SimSample {
                        positions,
                        velocities,
                        poses: state.poses(sim),
                    })
                }
                _ => None,
            };
            let states = world
                .states()
                .iter()
                .map(|state| state.read())
                .collect::<Result<_, _>>()?;
            self.writer()?.send(Job::State { time, states, sim })?;
        }
        if record_images {
            let images = self.images(world)?;
            self.writer()?.send(Job::Images { time, images })?;
        }
        Ok(())
    }

    fn end(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        if self.writer.is_none() {
            return Ok(());
        }
        self.follow_episodes(world)?;
        self.end_episode()?;
        self.writer()?.finish()
    }
}
