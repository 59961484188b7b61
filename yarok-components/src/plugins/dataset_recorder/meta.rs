//! A LeRobot v3 dataset's layout and its `meta/info.json` and `meta/stats.json`, as LeRobot's
//! code (`lerobot/datasets/utils.py`, `dataset_metadata.py`) writes them.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::{Value, json};
use yarok_core::BoxError;
use yarok_core::output_file::write_in_own_folder;

use super::stats::Summary;

/// The format version LeRobot checks before it opens a dataset.
pub(super) const CODEBASE_VERSION: &str = "v3.0";

/// Files in a chunk folder before the next folder begins.
pub(super) const CHUNKS_SIZE: u32 = 1000;

/// The size of a data file after which the next begins, in MB.
pub(super) const DATA_FILES_SIZE_IN_MB: u32 = 100;

/// The size of a video file after which the next begins, in MB (each episode's video is a file
/// of its own here, far below it).
const VIDEO_FILES_SIZE_IN_MB: u32 = 200;

const DATA_PATH: &str = "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet";
const VIDEO_PATH: &str = "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4";

/// The features LeRobot gives every frame, after the dataset's own.
pub(super) const INDEX_FEATURES: [(&str, &str); 5] = [
    ("timestamp", "float32"),
    ("frame_index", "int64"),
    ("episode_index", "int64"),
    ("index", "int64"),
    ("task_index", "int64"),
];

/// Which file of which chunk folder (`chunk-000/file-007`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct FileIndex {
    pub(super) chunk: u32,
    pub(super) file: u32,
}

impl FileIndex {
    /// The file after this one: the next chunk's first when this chunk is full.
    pub(super) fn next(self) -> Self {
        if self.file + 1 >= CHUNKS_SIZE {
            Self {
                chunk: self.chunk + 1,
                file: 0,
            }
        } else {
            Self {
                chunk: self.chunk,
                file: self.file + 1,
            }
        }
    }

    /// The `n`-th file (from 0).
    pub(super) fn nth(n: u64) -> Self {
        let chunks = u64::from(CHUNKS_SIZE);
        Self {
            chunk: u32::try_from(n / chunks).unwrap_or(u32::MAX),
            file: (n % chunks) as u32,
        }
    }

    /// `data/chunk-000/file-000.parquet` within `root`.
    pub(super) fn data_path(self, root: &Path) -> PathBuf {
        root.join(format!(
            "data/chunk-{:03}/file-{:03}.parquet",
            self.chunk, self.file
        ))
    }

    /// `videos/{key}/chunk-000/file-000.mp4` within `root`.
    pub(super) fn video_path(self, root: &Path, key: &str) -> PathBuf {
        root.join(format!(
            "videos/{key}/chunk-{:03}/file-{:03}.mp4",
            self.chunk, self.file
        ))
    }
}

/// One feature of a frame as `info.json` describes it.
#[derive(Debug, Clone, Serialize)]
pub(super) struct Feature {
    pub(super) dtype: &'static str,
    pub(super) shape: Vec<u32>,
    pub(super) names: Option<Value>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) info: Option<Value>,
}

impl Feature {
    /// A vector of `names.len()` 32-bit floats, its elements named.
    pub(super) fn vector(names: &[String]) -> Self {
        Self {
            dtype: "float32",
            shape: vec![u32::try_from(names.len()).unwrap_or(u32::MAX)],
            names: Some(json!(names)),
            info: None,
        }
    }

    /// One number of type `dtype`.
    pub(super) fn scalar(dtype: &'static str) -> Self {
        Self {
            dtype,
            shape: vec![1],
            names: None,
            info: None,
        }
    }

    /// An RGB video of `width` × `height` at `fps`, H.264 as `encoding` states.
    pub(super) fn video(width: u32, height: u32, fps: u32, encoding: &Value) -> Self {
        let mut info = json!({
            "video.height": height,
            "video.width": width,
            "video.codec": "h264",
            "video.pix_fmt": super::super::encoder::H264::PIXEL_FORMAT,
            "video.fps": fps,
            "video.channels": 3,
            "has_audio": false,
            "is_depth_map": false,
        });
        if let (Some(info), Some(encoding)) = (info.as_object_mut(), encoding.as_object()) {
            info.extend(encoding.clone());
        }
        Self {
            dtype: "video",
            shape: vec![height, width, 3],
            names: Some(json!(["height", "width", "channels"])),
            info: Some(info),
        }
    }

    /// Whether LeRobot keeps this feature in videos rather than in the data files.
    pub(super) fn is_video(&self) -> bool {
        self.dtype == "video"
    }
}

/// `meta/info.json`.
#[derive(Debug, Serialize)]
pub(super) struct Info<'a> {
    pub(super) codebase_version: &'static str,
    pub(super) robot_type: &'a str,
    pub(super) total_episodes: u64,
    pub(super) total_frames: u64,
    pub(super) total_tasks: u64,
    pub(super) chunks_size: u32,
    pub(super) data_files_size_in_mb: u32,
    pub(super) video_files_size_in_mb: u32,
    pub(super) fps: u32,
    pub(super) splits: BTreeMap<&'static str, String>,
    pub(super) data_path: &'static str,
    pub(super) video_path: Option<&'static str>,
    /// In the order frames hold them, written as one object.
    #[serde(serialize_with = "ordered_object")]
    pub(super) features: &'a [(String, Feature)],
}

impl<'a> Info<'a> {
    /// The info of a dataset of `features` at `fps`, with these totals.
    pub(super) fn new(
        robot_type: &'a str,
        fps: u32,
        features: &'a [(String, Feature)],
        total_episodes: u64,
        total_frames: u64,
        total_tasks: u64,
    ) -> Self {
        let has_videos = features.iter().any(|(_, feature)| feature.is_video());
        Self {
            codebase_version: CODEBASE_VERSION,
            robot_type,
            total_episodes,
            total_frames,
            total_tasks,
            chunks_size: CHUNKS_SIZE,
            data_files_size_in_mb: DATA_FILES_SIZE_IN_MB,
            video_files_size_in_mb: VIDEO_FILES_SIZE_IN_MB,
            fps,
            splits: BTreeMap::from([("train", format!("0:{total_episodes}"))]),
            data_path: DATA_PATH,
            video_path: has_videos.then_some(VIDEO_PATH),
            features,
        }
    }
}

fn ordered_object<S: serde::Serializer>(
    pairs: &[(String, Feature)],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.collect_map(pairs.iter().map(|(key, feature)| (key, feature)))
}

/// A statistic's values in the shape LeRobot gives them: `[v, …]` for a vector or a number,
/// `[[[r]], [[g]], [[b]]]` (channels × 1 × 1) for an image.
pub(super) fn shaped(values: &[f64], image: bool) -> Value {
    if image {
        json!(values.iter().map(|v| [[v]]).collect::<Vec<_>>())
    } else {
        json!(values)
    }
}

/// A feature's statistics as `stats.json` holds them.
pub(super) fn stats_json(summary: &Summary, image: bool) -> Value {
    let mut object = serde_json::Map::new();
    for (key, values) in &summary.values {
        object.insert((*key).to_owned(), shaped(values, image));
    }
    object.insert("count".to_owned(), json!([summary.count]));
    Value::Object(object)
}

/// Writes `value` as `path` (pretty JSON, as LeRobot's `write_json` does), creating its folder.
pub(super) fn write_json(path: &Path, value: &impl Serialize) -> Result<(), BoxError> {
    let text = serde_json::to_string_pretty(value)?;
    write_in_own_folder(path, text.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", path.display()).into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_fill_a_chunk_folder_then_the_next() {
        assert_eq!(FileIndex::nth(0), FileIndex { chunk: 0, file: 0 });
        assert_eq!(FileIndex::nth(1001), FileIndex { chunk: 1, file: 1 });
        assert_eq!(FileIndex::nth(999).next(), FileIndex::nth(1000));
        assert_eq!(
            FileIndex::nth(1001).video_path(Path::new("d"), "observation.images.top"),
            Path::new("d/videos/observation.images.top/chunk-001/file-001.mp4")
        );
    }

    #[test]
    fn info_keeps_the_features_in_frame_order_and_states_the_split() {
        let features = vec![
            (
                "observation.state".to_owned(),
                Feature::vector(&["a".into()]),
            ),
            ("timestamp".to_owned(), Feature::scalar("float32")),
        ];
        let info = serde_json::to_string(&Info::new("ur5e", 30, &features, 2, 60, 1)).unwrap();
        assert!(info.find("observation.state").unwrap() < info.find("timestamp").unwrap());
        assert!(info.contains(r#""splits":{"train":"0:2"}"#), "{info}");
        assert!(info.contains(r#""video_path":null"#), "{info}");
    }
}
