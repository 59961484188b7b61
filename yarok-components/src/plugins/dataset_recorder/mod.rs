//! [`DatasetRecorder`]: a run as a LeRobot v3 dataset — the joints' positions, the actuators'
//! commands and the cameras' and tactile sensors' images, frame by frame, episode by episode —
//! that LeRobot trains on.

mod episode;
mod folder;
mod meta;
mod stats;
mod tables;

use std::path::PathBuf;

use serde_json::{Value, json};
use yarok_core::BoxError;
use yarok_core::runtime::{Episode, Happening, Plugin, World};
use yarok_mjc::SimBackend;

use self::episode::{EpisodeRecording, Frame};
use self::folder::DatasetFolder;
use self::meta::{Feature, INDEX_FEATURES, Info, stats_json, write_json};
use self::stats::FeatureStats;
use self::tables::{DataFiles, EpisodeRow, VECTOR_FEATURES, Widths, write_episodes, write_tasks};
use super::encoder::H264;
use crate::features::Features;

/// What and how a [`DatasetRecorder`] records (`[plugins.dataset]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DatasetRecorderSettings {
    /// The dataset's folder: created, or replaced if it holds a dataset yarok wrote and
    /// nothing else; a folder holding anything else, or one another run writes into, is
    /// refused. The dataset is written beside it (`.NAME.yarok-partial`) and moved into place
    /// when the run ends, so the folder holds the old dataset or the new one, whole.
    pub path: PathBuf,
    /// Frames a second of platform time (LeRobot's `fps`).
    pub fps: u32,
    /// Cameras of the model to record as videos, by name (`overview`); components' RGB images
    /// (tactile sensors, cameras) are recorded through their probes anyway.
    pub cameras: Vec<String>,
    /// Width and height of the cameras' images (even numbers, as H.264 needs).
    pub size: [u32; 2],
    /// Render the cameras with MuJoCo's shadows, reflections and multisampling (default:
    /// without).
    pub quality: bool,
    /// x264's constant rate factor: 0 is lossless; 18, the default, is near it.
    pub crf: u32,
    /// What `info.json` names the robot (default: the world's tag).
    pub robot_type: Option<String>,
}

impl Default for DatasetRecorderSettings {
    fn default() -> Self {
        Self {
            path: PathBuf::from("dataset"),
            fps: 30,
            cameras: Vec::new(),
            size: [640, 480],
            quality: false,
            crf: 18,
            robot_type: None,
        }
    }
}

/// Frames from one keyframe to the next: LeRobot's default, so that training reads any frame
/// quickly.
const KEYFRAME_INTERVAL: u32 = 2;

/// Records a run as a [LeRobot](https://github.com/huggingface/lerobot) v3 dataset, as
/// LeRobot's own code lays it out: `meta/info.json` (features, `fps`, totals),
/// `meta/stats.json`, `meta/tasks.parquet`, `meta/episodes/chunk-000/file-000.parquet` (each
/// episode's frames, files, tasks and statistics), `data/chunk-000/file-000.parquet` (the
/// frames) and `videos/{key}/chunk-000/file-{episode}.mp4`.
///
/// Every frame, `fps` times a second of platform time, holds:
/// - the world's [`Features`], as a policy sees them in the world (yarok's Gymnasium
///   environments observe the same): `observation.state` (every hinge's and slide's
///   position), `observation.environment_state` (every free body's pose), `action` (each
///   component's actuation as the behaviour commands it for the period that follows: an
///   arm's joint targets where its motion is due at the next frame, a gripper's position —
///   so that `action` given at a frame leads to the next frame's state, as a leader arm's
///   command leads its follower in LeRobot's datasets; see [`Features::action`]) and
///   `observation.images.{probe}` for every RGB probe
///   (`observation.images.arm.gripper.left_digit.image`: a tactile sensor's image) and
///   `observation.images.{camera}` for each camera asked for: H.264 MP4 videos (`yuv420p`, a
///   keyframe every 2 frames, `crf` as set), through `ffmpeg`;
/// - `timestamp` (`frame_index / fps`), `frame_index`, `episode_index`, `index` and
///   `task_index`: the task the behaviour last set ([`Pl::set_task`](yarok_core::runtime::Pl::set_task);
///   before any, the world's tag).
///
/// Frame `i` of an episode is taken at the first tick at or after `i / fps` from the episode's
/// start. Each episode a behaviour begins ([`Pl::begin_episode`](yarok_core::runtime::Pl::begin_episode))
/// is an episode of the dataset, numbered from 0 in the order they ran; what happens outside
/// them is not recorded. A run that begins none is one episode. Statistics (`min`, `max`,
/// `mean`, `std`, `count`, quantiles `q01` … `q99`) are exact: of every frame's numbers and every
/// pixel (colours from 0 to 1). Depth images are not recorded.
///
/// A sharded run (`[platform] shard = "1/3"`) writes its share as a dataset of its own beside
/// `path` (`dataset_1_of_3`); LeRobot's `aggregate_datasets` merges the shards' datasets into
/// one (see the README).
///
/// Registered by `yarok::platform()` as `dataset`, with the feature `dataset`:
///
/// ```toml
/// [plugins.dataset]
/// path = "out/pick_and_place"
/// fps = 30
/// cameras = ["overview"]
/// ```
#[derive(Debug)]
pub struct DatasetRecorder {
    settings: DatasetRecorderSettings,
    /// Where the dataset is being written (beside the shard's folder, until the run ends).
    root: PathBuf,
    /// The shard's folder, claimed when the run starts.
    folder: Option<DatasetFolder>,
    robot_type: String,
    /// What a frame holds, found when the run starts.
    observed: Option<Features>,
    widths: Widths,
    /// Every feature, in frame order.
    features: Vec<(String, Feature)>,
    /// The video features: the RGB probes', then the cameras'.
    videos: Vec<(String, H264)>,
    data: Option<DataFiles>,
    /// The dataset's tasks, in the order they were first set, and the one frames are of now.
    tasks: Vec<String>,
    task: Option<usize>,
    episodes: Vec<EpisodeRow>,
    stats: Vec<(String, FeatureStats)>,
    frames: u64,
    /// The episode being taken, and when it began (`None`: the run's start, for a run that
    /// begins no episode of its own).
    recording: Option<(EpisodeRecording, Option<Episode>)>,
}

impl DatasetRecorder {
    /// A recorder with these settings; the dataset is begun when the run starts.
    ///
    /// # Errors
    ///
    /// When `fps` is 0, or the size is not even and positive.
    pub fn new(settings: DatasetRecorderSettings) -> Result<Self, BoxError> {
        if settings.fps == 0 {
            return Err("`fps` must be at least 1".into());
        }
        if settings.size.iter().any(|s| *s == 0 || s % 2 == 1) {
            return Err(format!("`size` {:?} must be even numbers above 0", settings.size).into());
        }
        Ok(Self {
            root: settings.path.clone(),
            folder: None,
            settings,
            robot_type: String::new(),
            observed: None,
            widths: [0; 3],
            features: Vec::new(),
            videos: Vec::new(),
            data: None,
            tasks: Vec::new(),
            task: None,
            episodes: Vec::new(),
            stats: Vec::new(),
            frames: 0,
            recording: None,
        })
    }

    /// The H.264 video of `width` × `height` images, as the settings encode it.
    fn video(&self, key: &str, width: u32, height: u32) -> Result<H264, BoxError> {
        if width % 2 == 1 || height % 2 == 1 {
            return Err(format!(
                "{key}'s images are {width}×{height}: H.264 in yuv420p needs even sizes"
            )
            .into());
        }
        Ok(H264 {
            size: [width, height],
            fps: f64::from(self.settings.fps),
            keyframe_interval: Some(KEYFRAME_INTERVAL),
            crf: Some(self.settings.crf),
        })
    }

    /// Finds the features of the world: its [`Features`], with the cameras asked for.
    fn find_features(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let settings = &self.settings;
        let observed = Features::of(world, &settings.cameras, settings.size, settings.quality)?;
        let vectors = [
            observed.state_names(),
            observed.environment_names(),
            observed.action_names(),
        ];
        self.widths = vectors.map(<[String]>::len);
        for (name, names) in VECTOR_FEATURES.into_iter().zip(vectors) {
            if !names.is_empty() {
                self.features.push((name.into(), Feature::vector(names)));
            }
        }
        for image in observed.images() {
            let [width, height] = image.size;
            let video = self.video(&image.key, width, height)?;
            self.videos.push((image.key.clone(), video));
        }
        let encoding = json!({"video.g": KEYFRAME_INTERVAL, "video.crf": self.settings.crf});
        for (key, video) in &self.videos {
            let [width, height] = video.size;
            let feature = Feature::video(width, height, self.settings.fps, &encoding);
            self.features.push((key.clone(), feature));
        }
        for (name, dtype) in INDEX_FEATURES {
            self.features.push((name.into(), Feature::scalar(dtype)));
        }
        self.observed = Some(observed);
        Ok(())
    }

    /// The index of `task` among the dataset's tasks, added if new.
    fn task_index(&mut self, task: &str) -> usize {
        match self.tasks.iter().position(|known| known == task) {
            Some(index) => index,
            None => {
                self.tasks.push(task.to_owned());
                self.tasks.len() - 1
            }
        }
    }

    /// Begins the dataset's next episode.
    fn begin(&mut self, episode: Option<Episode>) -> Result<(), BoxError> {
        let recording = EpisodeRecording::begin(
            &self.root,
            self.episodes.len() as u64,
            self.frames,
            self.settings.fps,
            self.widths,
            &self.videos,
        )?;
        self.recording = Some((recording, episode));
        Ok(())
    }

    /// Writes the episode being taken, if it has a frame.
    fn finish(&mut self) -> Result<(), BoxError> {
        let Some((recording, _)) = self.recording.take() else {
            return Ok(());
        };
        if recording.len() == 0 {
            recording.abandon();
            return Ok(());
        }
        let data = self.data.as_mut().ok_or("the dataset has not been begun")?;
        let (row, stats) = recording.finish(data, &self.tasks)?;
        self.frames += row.length;
        self.episodes.push(row);
        if self.stats.is_empty() {
            self.stats = stats;
        } else {
            for ((_, mine), (_, theirs)) in self.stats.iter_mut().zip(&stats) {
                mine.merge(theirs);
            }
        }
        Ok(())
    }

    /// Follows the tasks set and the episodes begun and ended since the last step.
    fn follow(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        for happening in world.happenings().iter() {
            match happening {
                Happening::TaskSet(task) => self.task = Some(self.task_index(task)),
                Happening::EpisodeBegan(episode) => {
                    match self.recording.take() {
                        // The run is not one episode: what came before this one is not kept.
                        Some((whole_run, None)) => whole_run.abandon(),
                        ended => {
                            self.recording = ended;
                            self.finish()?;
                        }
                    }
                    self.begin(Some(*episode))?;
                }
                Happening::EpisodeEnded(_) => self.finish()?,
                Happening::Logged(_) => {}
            }
        }
        Ok(())
    }

    /// The frame of the world now.
    fn take_frame(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let observed = self
            .observed
            .as_mut()
            .ok_or("the dataset's features have not been found")?;
        let observation = observed.observe(world)?;
        let action = observed.action(world, 1.0 / f64::from(self.settings.fps));
        let task = match self.task {
            Some(task) => task,
            None => {
                let world_tag = world.composition().instances[0].tag.clone();
                let task = self.task_index(&world_tag);
                self.task = Some(task);
                task
            }
        };
        let Some((recording, _)) = &mut self.recording else {
            return Ok(());
        };
        recording.add(Frame {
            vectors: [&observation.state, &observation.environment_state, &action],
            task,
            images: observation.images,
        })
    }

    /// Writes the dataset's tables and `meta` files.
    fn write_meta(&self) -> Result<(), BoxError> {
        write_tasks(&self.root, &self.tasks)?;
        write_episodes(&self.root, &self.episodes)?;
        let info = Info::new(
            &self.robot_type,
            self.settings.fps,
            &self.features,
            self.episodes.len() as u64,
            self.frames,
            self.tasks.len() as u64,
        );
        write_json(&self.root.join("meta/info.json"), &info)?;
        let mut stats = serde_json::Map::new();
        for (name, feature) in &self.stats {
            let (summary, image) = feature.summary();
            stats.insert(name.clone(), stats_json(&summary, image));
        }
        write_json(&self.root.join("meta/stats.json"), &Value::Object(stats))
    }
}

impl Plugin for DatasetRecorder {
    fn writes(&self) -> Vec<PathBuf> {
        vec![self.settings.path.clone()]
    }

    fn name(&self) -> String {
        format!("dataset ({})", self.settings.path.display())
    }

    fn environments(&self) -> Vec<&'static str> {
        crate::plugins::only_sim()
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let shard = world.pl().shard();
        let mut destination = self.settings.path.clone();
        if !shard.is_whole() {
            let mut name = destination.file_name().unwrap_or_default().to_owned();
            name.push(format!("_{}_of_{}", shard.index, shard.count));
            destination = destination.with_file_name(name);
        }
        self.robot_type = match &self.settings.robot_type {
            Some(robot_type) => robot_type.clone(),
            None => world.composition().instances[0].tag.clone(),
        };
        self.find_features(world)?;
        let folder = DatasetFolder::claim(&destination)?;
        self.root = folder.partial().to_owned();
        self.folder = Some(folder);
        self.data = Some(DataFiles::new(&self.root, self.widths));
        self.begin(None)
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.follow(world)?;
        let (Some(sim), Some((recording, episode))) =
            (world.backend::<SimBackend>(), &self.recording)
        else {
            return Ok(());
        };
        let tick = world.pl().ticks();
        let time = match episode {
            Some(episode) => episode.time_at(tick, world.pl().timestep()),
            None => sim.data().time(),
        };
        if time + 1e-9 >= recording.next_frame_time() {
            self.take_frame(world)?;
        }
        Ok(())
    }

    fn end(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        if self.data.is_none() {
            return Ok(());
        }
        self.follow(world)?;
        self.finish()?;
        if let Some(data) = &mut self.data {
            data.close()?;
        }
        self.write_meta()?;
        match self.folder.take() {
            Some(folder) => folder.commit(),
            None => Ok(()),
        }
    }
}
