//! [`EpisodeRecording`]: one episode of a dataset as it is taken — its frames' numbers kept,
//! its videos streamed to their encoders — and written when it ends.

use std::path::{Path, PathBuf};

use yarok_core::BoxError;

use super::super::encoder::{Encoder, H264};
use super::meta::{FileIndex, INDEX_FEATURES};
use super::stats::{FeatureStats, ImageStats, NumberStats};
use super::tables::{DataFiles, EpisodeRow, Frames, VECTOR_FEATURES, Widths};

/// A video feature being filmed for the episode.
#[derive(Debug)]
struct VideoStream {
    key: String,
    path: PathBuf,
    encoder: Encoder,
    stats: ImageStats,
}

/// What a frame holds besides its indices.
#[derive(Debug)]
pub(super) struct Frame<'a> {
    /// Each of the vector features' numbers, in [`VECTOR_FEATURES`]' order.
    pub(super) vectors: [&'a [f64]; 3],
    /// The frame's task, by its index among the dataset's tasks.
    pub(super) task: usize,
    /// Each video feature's image, RGB, in the order the recording was begun with.
    pub(super) images: Vec<Vec<u8>>,
}

/// An episode of the dataset being taken.
#[derive(Debug)]
pub(super) struct EpisodeRecording {
    index: u64,
    /// The dataset's `index` of the episode's first frame.
    first: u64,
    fps: u32,
    widths: Widths,
    frames: Frames,
    /// The tasks the frames were of, by index, each once, in the order they came.
    tasks: Vec<usize>,
    videos: Vec<VideoStream>,
}

impl EpisodeRecording {
    /// Begins episode `index` of the dataset in `root`, whose first frame is the dataset's
    /// `first`: one encoder for each video feature, `(key, video)`.
    pub(super) fn begin(
        root: &Path,
        index: u64,
        first: u64,
        fps: u32,
        widths: Widths,
        videos: &[(String, H264)],
    ) -> Result<Self, BoxError> {
        let file = FileIndex::nth(index);
        let mut streams = Vec::new();
        for (key, video) in videos {
            let path = file.video_path(root, key);
            if let Some(folder) = path.parent() {
                std::fs::create_dir_all(folder)
                    .map_err(|e| format!("cannot create {}: {e}", folder.display()))?;
            }
            streams.push(VideoStream {
                key: key.clone(),
                encoder: Encoder::start(video, path.clone())?,
                path,
                stats: ImageStats::default(),
            });
        }
        Ok(Self {
            index,
            first,
            fps,
            widths,
            frames: Frames::default(),
            tasks: Vec::new(),
            videos: streams,
        })
    }

    /// How many frames it has.
    pub(super) fn len(&self) -> u64 {
        self.frames.frame_index.len() as u64
    }

    /// The time of the next frame, from the episode's start: frame `i` is due at `i / fps`.
    pub(super) fn next_frame_time(&self) -> f64 {
        self.len() as f64 / f64::from(self.fps)
    }

    /// Adds a frame.
    pub(super) fn add(&mut self, frame: Frame<'_>) -> Result<(), BoxError> {
        let number = self.len();
        let as_i64 = |n: u64| i64::try_from(n).unwrap_or(i64::MAX);
        for (column, values) in self.frames.vectors.iter_mut().zip(frame.vectors) {
            column.extend(values.iter().map(|v| *v as f32));
        }
        self.frames
            .timestamp
            .push((number as f64 / f64::from(self.fps)) as f32);
        self.frames.frame_index.push(as_i64(number));
        self.frames.episode_index.push(as_i64(self.index));
        self.frames.index.push(as_i64(self.first + number));
        self.frames.task_index.push(as_i64(frame.task as u64));
        if !self.tasks.contains(&frame.task) {
            self.tasks.push(frame.task);
        }
        for (video, image) in self.videos.iter_mut().zip(frame.images) {
            video.stats.add(&image);
            video
                .encoder
                .send(image)
                .map_err(|e| format!("video {}: {e}", video.key))?;
        }
        Ok(())
    }

    /// Leaves the episode unwritten: its encoders stopped, its videos removed.
    pub(super) fn abandon(self) {
        for video in self.videos {
            drop(video.encoder);
            let _gone_already = std::fs::remove_file(&video.path);
        }
    }

    /// Writes the episode: its frames to `data`, its videos finished. Returns its row of
    /// `meta/episodes` (naming its tasks from `tasks`, the dataset's), and each feature's
    /// statistics as gathered, for the dataset's.
    pub(super) fn finish(
        self,
        data: &mut DataFiles,
        tasks: &[String],
    ) -> Result<(EpisodeRow, Vec<(String, FeatureStats)>), BoxError> {
        let length = self.len();
        let file = data.append(&self.frames)?;
        let mut stats = Vec::new();
        for ((name, values), width) in VECTOR_FEATURES
            .into_iter()
            .zip(&self.frames.vectors)
            .zip(self.widths)
        {
            if width > 0 {
                let mut numbers = NumberStats::new(width);
                for frame in values.chunks_exact(width) {
                    numbers.add(frame.iter().map(|v| f64::from(*v)));
                }
                stats.push((name.to_owned(), FeatureStats::Numbers(numbers)));
            }
        }
        let mut videos = Vec::new();
        let duration = length as f64 / f64::from(self.fps);
        for video in self.videos {
            video
                .encoder
                .finish()
                .map_err(|e| format!("video {}: {e}", video.key))?;
            videos.push((video.key.clone(), FileIndex::nth(self.index), duration));
            stats.push((video.key, FeatureStats::Image(video.stats, length)));
        }
        let index_columns: [Vec<f64>; 5] = [
            self.frames
                .timestamp
                .iter()
                .map(|v| f64::from(*v))
                .collect(),
            as_f64(&self.frames.frame_index),
            as_f64(&self.frames.episode_index),
            as_f64(&self.frames.index),
            as_f64(&self.frames.task_index),
        ];
        for ((name, _), column) in INDEX_FEATURES.iter().zip(index_columns) {
            let mut numbers = NumberStats::new(1);
            for value in column {
                numbers.add([value]);
            }
            stats.push(((*name).to_owned(), FeatureStats::Numbers(numbers)));
        }
        let row = EpisodeRow {
            index: self.index,
            tasks: self.tasks.iter().map(|task| tasks[*task].clone()).collect(),
            length,
            data: file,
            from: self.first,
            to: self.first + length,
            videos,
            stats: stats
                .iter()
                .map(|(name, stats)| {
                    let (summary, image) = stats.summary();
                    (name.clone(), summary, image)
                })
                .collect(),
        };
        Ok((row, stats))
    }
}

fn as_f64(values: &[i64]) -> Vec<f64> {
    values.iter().map(|v| *v as f64).collect()
}
