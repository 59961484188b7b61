//! [`McapFile`]: one MCAP file of a recording — the run's or an episode's — with its channels,
//! encoding each message as its profile says, in zstd-compressed chunks.

use std::collections::BTreeMap;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_core::output::head;
use yarok_core::output_file::OutputFile;
use yarok_core::output_lock::OutputLock;
use yarok_mjc::Pose;

use crate::plugins::recording_profile::{JointValues, MessageKind, RecordingProfile, nanoseconds};

/// The library an MCAP file's header names when yarok recorded it (with yarok's version).
const LIBRARY: &str = "yarok";

/// Whether the file at `path` is an MCAP recording yarok made: its header names yarok as the
/// library that wrote it.
fn recorded_by_yarok(path: &Path) -> std::io::Result<bool> {
    const MAGIC: &[u8] = b"\x89MCAP0\r\n";
    let bytes = head(path, 4096)?;
    let string_at = |at: usize| -> Option<(&[u8], usize)> {
        let length = u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?) as usize;
        Some((bytes.get(at + 4..at + 4 + length)?, at + 4 + length))
    };
    // The magic, then the header record: opcode 1, its length (u64), profile, library.
    let library = bytes
        .starts_with(MAGIC)
        .then_some(())
        .filter(|()| bytes.get(MAGIC.len()) == Some(&1))
        .and_then(|()| string_at(MAGIC.len() + 9))
        .and_then(|(_, next)| string_at(next))
        .map(|(library, _)| library);
    Ok(library.is_some_and(|library| {
        library == LIBRARY.as_bytes() || library.starts_with(format!("{LIBRARY} ").as_bytes())
    }))
}

/// What a recording's files hold, found once at the start of the run.
#[derive(Debug, Clone, Default)]
pub(super) struct Layout {
    /// In `sim`: the joints' names and the transform frames' names.
    pub(super) sim: Option<SimNames>,
    /// One channel per probe, then per camera recorded.
    pub(super) images: Vec<ImageChannel>,
    /// One channel per component's named state, by its path (`/arm/state`).
    pub(super) states: Vec<String>,
}

/// The names a `sim` world's state is recorded under.
#[derive(Debug, Clone)]
pub(super) struct SimNames {
    pub(super) joints: Arc<[String]>,
    pub(super) frames: Arc<[String]>,
}

/// A channel of images.
#[derive(Debug, Clone)]
pub(super) struct ImageChannel {
    pub(super) topic: String,
    pub(super) kind: MessageKind,
    /// The channel's metadata (a depth channel's unit).
    pub(super) metadata: BTreeMap<String, String>,
    /// The transform frame the images are in.
    pub(super) frame: String,
}

/// A `sim` world's state at one time.
#[derive(Debug)]
pub(super) struct SimSample {
    pub(super) positions: Vec<f64>,
    pub(super) velocities: Vec<f64>,
    pub(super) poses: Vec<Pose>,
}

#[derive(Debug, Default)]
struct Channels {
    /// In `sim`: joint states and transforms.
    sim: Option<(u16, u16)>,
    clock: Option<u16>,
    log: u16,
    images: Vec<u16>,
    states: Vec<u16>,
}

/// See the [module](self).
pub(super) struct McapFile {
    path: PathBuf,
    profile: Arc<dyn RecordingProfile>,
    layout: Layout,
    writer: mcap::Writer<BufWriter<OutputFile>>,
    channels: Channels,
    sequence: u32,
    /// Held while the file is written: a second run recording to the same path is refused.
    _lock: OutputLock,
}

impl std::fmt::Debug for McapFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("McapFile")
            .field("path", &self.path)
            .finish()
    }
}

impl McapFile {
    /// Creates `path` (and its folder) with `metadata` and a channel for everything `layout`
    /// holds.
    ///
    /// # Errors
    ///
    /// When the file cannot be created or written, naming it.
    pub(super) fn create(
        path: PathBuf,
        profile: &Arc<dyn RecordingProfile>,
        layout: &Layout,
        metadata: &mcap::records::Metadata,
    ) -> Result<Self, BoxError> {
        // The file first (it makes the folder the lock goes in); nothing is at the path until
        // the commit, so a second run refused by the lock leaves no trace.
        let file = OutputFile::create(&path, "recording", recorded_by_yarok)?;
        let lock = OutputLock::take(&path, &format!("the recording {}", path.display()))?;
        let options = mcap::WriteOptions::new()
            .compression(Some(mcap::Compression::Zstd))
            .profile(profile.mcap_profile())
            .library(format!("{LIBRARY} {}", env!("CARGO_PKG_VERSION")));
        let mut writer = options
            .create(BufWriter::new(file))
            .map_err(|e| failed(&path, e))?;
        writer
            .write_metadata(metadata)
            .map_err(|e| failed(&path, e))?;
        let mut file = Self {
            path,
            profile: Arc::clone(profile),
            layout: layout.clone(),
            writer,
            channels: Channels::default(),
            sequence: 0,
            _lock: lock,
        };
        file.channels.log = file.channel(MessageKind::Log, "/log", &BTreeMap::new())?;
        for image in &layout.images {
            let channel = file.channel(image.kind, &image.topic, &image.metadata)?;
            file.channels.images.push(channel);
        }
        for topic in &layout.states {
            let channel = file.channel(MessageKind::State, topic, &BTreeMap::new())?;
            file.channels.states.push(channel);
        }
        if layout.sim.is_some() {
            let none = BTreeMap::new();
            file.channels.sim = Some((
                file.channel(MessageKind::JointState, "/joint_states", &none)?,
                file.channel(MessageKind::Transforms, "/tf", &none)?,
            ));
        }
        if file.profile.schema(MessageKind::Clock).is_some() {
            file.channels.clock =
                Some(file.channel(MessageKind::Clock, "/clock", &BTreeMap::new())?);
        }
        Ok(file)
    }

    fn channel(
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
            log_time: nanoseconds(time),
            publish_time: nanoseconds(time),
        };
        let written = self.writer.write_to_known_channel(&header, data);
        written.map_err(|e| failed(&self.path, e))
    }

    /// Writes a behaviour's log line.
    pub(super) fn log(&mut self, time: f64, text: &str) -> Result<(), BoxError> {
        let message = self.profile.log(time, text);
        self.write(self.channels.log, time, &message)
    }

    /// Writes the clock (if the profile records it), the components' named states (one a
    /// channel, in the layout's order) and, in `sim`, the joints and frames.
    pub(super) fn state(
        &mut self,
        time: f64,
        states: &[serde_json::Value],
        sim: Option<&SimSample>,
    ) -> Result<(), BoxError> {
        if let (Some(channel), Some(message)) = (self.channels.clock, self.profile.clock(time)) {
            self.write(channel, time, &message)?;
        }
        for (index, value) in states.iter().enumerate() {
            let channel = *self
                .channels
                .states
                .get(index)
                .ok_or_else(|| format!("no channel for state {index}"))?;
            let message = self.profile.state(time, value);
            self.write(channel, time, &message)?;
        }
        let (Some(sample), Some(names), Some((joint_states, transforms))) =
            (sim, &self.layout.sim, self.channels.sim)
        else {
            return Ok(());
        };
        let joints = JointValues {
            names: &names.joints,
            positions: &sample.positions,
            velocities: &sample.velocities,
        };
        let joints = self.profile.joint_state(time, &joints);
        let poses = self.profile.transforms(time, &names.frames, &sample.poses);
        self.write(joint_states, time, &joints)?;
        self.write(transforms, time, &poses)
    }

    /// Writes an image of every image channel, in the layout's order.
    pub(super) fn images(&mut self, time: f64, images: &[ProbeImage]) -> Result<(), BoxError> {
        for (index, image) in images.iter().enumerate() {
            let (Some(&channel), Some(layout)) = (
                self.channels.images.get(index),
                self.layout.images.get(index),
            ) else {
                return Err(format!("no channel for image {index}").into());
            };
            let message = self.profile.image(time, &layout.frame, image)?;
            self.write(channel, time, &message)?;
        }
        Ok(())
    }

    /// Writes the summary and closes the file.
    pub(super) fn finish(mut self) -> Result<(), BoxError> {
        self.writer.finish().map_err(|e| failed(&self.path, e))?;
        let file = self.writer.into_inner();
        file.into_inner()
            .map_err(|e| failed(&self.path, mcap::McapError::Io(e.into_error())))?
            .commit()?;
        Ok(())
    }
}

fn failed(path: &Path, error: mcap::McapError) -> BoxError {
    let error = yarok_core::report::one_line(&error);
    format!("cannot write {}: {error}", path.display()).into()
}
