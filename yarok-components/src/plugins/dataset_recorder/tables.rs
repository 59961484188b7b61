//! A LeRobot v3 dataset's Parquet tables: the frames (`data/`), one row per episode
//! (`meta/episodes/`) and the tasks (`meta/tasks.parquet`), in the Arrow types LeRobot's
//! `datasets` features read them as.

use std::collections::HashMap;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use arrow_array::builder::{Float64Builder, Int64Builder, ListBuilder, StringBuilder};
use arrow_array::{
    ArrayRef, FixedSizeListArray, Float32Array, Float64Array, Int64Array, RecordBatch, StringArray,
};
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use parquet::arrow::ArrowWriter;
use parquet::basic::Compression;
use parquet::file::properties::WriterProperties;
use yarok_core::BoxError;
use yarok_core::output_file::file_in_own_folder;

use super::meta::{DATA_FILES_SIZE_IN_MB, FileIndex};
use super::stats::Summary;

/// One episode's frames, column by column.
#[derive(Debug, Default)]
pub(super) struct Frames {
    /// The vector features' numbers, frame after frame, in [`VECTOR_FEATURES`]' order
    /// ([`Widths`] values a frame each).
    pub(super) vectors: [Vec<f32>; 3],
    pub(super) timestamp: Vec<f32>,
    pub(super) frame_index: Vec<i64>,
    pub(super) episode_index: Vec<i64>,
    pub(super) index: Vec<i64>,
    pub(super) task_index: Vec<i64>,
}

/// The vector features of a frame, in their order in the tables.
pub(super) const VECTOR_FEATURES: [&str; 3] = [
    "observation.state",
    "observation.environment_state",
    "action",
];

/// How wide each of [`VECTOR_FEATURES`] is; a vector of no element is left out.
pub(super) type Widths = [usize; 3];

/// The elements of a vector column, as `datasets` names them.
fn float_item() -> Arc<Field> {
    Arc::new(Field::new("item", DataType::Float32, true))
}

fn fixed_size_list(values: &[f32], width: usize) -> Result<ArrayRef, BoxError> {
    let size = i32::try_from(width)?;
    let values = Arc::new(Float32Array::from(values.to_vec()));
    Ok(Arc::new(FixedSizeListArray::try_new(
        float_item(),
        size,
        values,
        None,
    )?))
}

/// The frames' schema: each vector as a fixed-size list of 32-bit floats (a `datasets`
/// `Sequence` of known length), then LeRobot's index columns.
fn frame_schema(widths: Widths) -> SchemaRef {
    let mut fields = Vec::new();
    for (name, width) in VECTOR_FEATURES.into_iter().zip(widths) {
        if width > 0 {
            let width = i32::try_from(width).unwrap_or(i32::MAX);
            let list = DataType::FixedSizeList(float_item(), width);
            fields.push(Field::new(name, list, true));
        }
    }
    fields.push(Field::new("timestamp", DataType::Float32, true));
    for name in ["frame_index", "episode_index", "index", "task_index"] {
        fields.push(Field::new(name, DataType::Int64, true));
    }
    Arc::new(Schema::new(fields))
}

/// Snappy-compressed, as LeRobot writes its tables.
fn properties() -> WriterProperties {
    WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .build()
}

/// The data files, filled episode after episode, each episode a row group; the next file
/// begins once one passes LeRobot's size.
pub(super) struct DataFiles {
    root: PathBuf,
    widths: Widths,
    schema: SchemaRef,
    current: FileIndex,
    writer: Option<ArrowWriter<File>>,
}

impl std::fmt::Debug for DataFiles {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DataFiles")
            .field("root", &self.root)
            .field("current", &self.current)
            .finish()
    }
}

impl DataFiles {
    /// Data files in dataset `root`, of frames this wide.
    pub(super) fn new(root: &Path, widths: Widths) -> Self {
        Self {
            root: root.to_owned(),
            widths,
            schema: frame_schema(widths),
            current: FileIndex::default(),
            writer: None,
        }
    }

    /// Writes an episode's frames; the file they went to.
    pub(super) fn append(&mut self, frames: &Frames) -> Result<FileIndex, BoxError> {
        let path = self.current.data_path(&self.root);
        let failed = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
        let mut columns = Vec::new();
        for (values, width) in frames.vectors.iter().zip(self.widths) {
            if width > 0 {
                columns.push(fixed_size_list(values, width)?);
            }
        }
        columns.push(Arc::new(Float32Array::from(frames.timestamp.clone())));
        for column in [
            &frames.frame_index,
            &frames.episode_index,
            &frames.index,
            &frames.task_index,
        ] {
            columns.push(Arc::new(Int64Array::from(column.clone())));
        }
        let batch = RecordBatch::try_new(Arc::clone(&self.schema), columns)?;
        let writer = match &mut self.writer {
            Some(writer) => writer,
            None => {
                let file = create(&path)?;
                let writer =
                    ArrowWriter::try_new(file, Arc::clone(&self.schema), Some(properties()))
                        .map_err(|e| failed(&e))?;
                self.writer.insert(writer)
            }
        };
        writer.write(&batch).map_err(|e| failed(&e))?;
        writer.flush().map_err(|e| failed(&e))?;
        let written = self.current;
        if writer.bytes_written() >= DATA_FILES_SIZE_IN_MB as usize * 1024 * 1024 {
            self.close()?;
            self.current = self.current.next();
        }
        Ok(written)
    }

    /// Ends the file being written.
    pub(super) fn close(&mut self) -> Result<(), BoxError> {
        if let Some(writer) = self.writer.take() {
            let path = self.current.data_path(&self.root);
            writer
                .close()
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        }
        Ok(())
    }
}

/// `path`, its folder created.
fn create(path: &Path) -> Result<File, BoxError> {
    file_in_own_folder(path).map_err(|e| format!("cannot create {}: {e}", path.display()).into())
}

/// Writes `columns` as one table in `path`, with `metadata` in its schema.
fn write_table(
    path: &Path,
    columns: Vec<(String, ArrayRef)>,
    metadata: HashMap<String, String>,
) -> Result<(), BoxError> {
    let batch = RecordBatch::try_from_iter(columns)?;
    let schema = Arc::new(batch.schema().as_ref().clone().with_metadata(metadata));
    let batch = batch.with_schema(Arc::clone(&schema))?;
    let failed = |e: parquet::errors::ParquetError| format!("cannot write {}: {e}", path.display());
    let mut writer =
        ArrowWriter::try_new(create(path)?, schema, Some(properties())).map_err(failed)?;
    writer.write(&batch).map_err(failed)?;
    writer.close().map_err(failed)?;
    Ok(())
}

/// What `meta/episodes` says of one episode.
#[derive(Debug, Clone)]
pub(super) struct EpisodeRow {
    pub(super) index: u64,
    /// Its tasks, each once, in the order they were first set.
    pub(super) tasks: Vec<String>,
    pub(super) length: u64,
    /// The data file its frames are in, and their `index` range (`from` ≤ index < `to`).
    pub(super) data: FileIndex,
    pub(super) from: u64,
    pub(super) to: u64,
    /// Each video feature's file, which holds this episode from its first frame to `duration`.
    pub(super) videos: Vec<(String, FileIndex, f64)>,
    /// Each feature's statistics, and whether it is an image.
    pub(super) stats: Vec<(String, Summary, bool)>,
}

fn int64_column(rows: &[EpisodeRow], value: impl Fn(&EpisodeRow) -> u64) -> ArrayRef {
    Arc::new(Int64Array::from_iter_values(
        rows.iter()
            .map(|row| i64::try_from(value(row)).unwrap_or(i64::MAX)),
    ))
}

/// A statistic's column: a list of numbers per episode, or for an image, channels × 1 × 1.
fn stat_column(rows: &[EpisodeRow], feature: usize, key: &str, image: bool) -> ArrayRef {
    let values = |row: &EpisodeRow| {
        row.stats[feature]
            .1
            .values
            .get(key)
            .cloned()
            .unwrap_or_default()
    };
    if image {
        let mut column =
            ListBuilder::new(ListBuilder::new(ListBuilder::new(Float64Builder::new())));
        for row in rows {
            for value in values(row) {
                let channel = column.values();
                channel.values().values().append_value(value);
                channel.values().append(true);
                channel.append(true);
            }
            column.append(true);
        }
        Arc::new(column.finish())
    } else {
        let mut column = ListBuilder::new(Float64Builder::new());
        for row in rows {
            column.values().append_slice(&values(row));
            column.append(true);
        }
        Arc::new(column.finish())
    }
}

/// Writes `meta/episodes/chunk-000/file-000.parquet` in `root`: one row per episode, with the
/// columns LeRobot's `save_episode` gives it.
pub(super) fn write_episodes(root: &Path, rows: &[EpisodeRow]) -> Result<(), BoxError> {
    let Some(first) = rows.first() else {
        return Ok(());
    };
    let mut columns: Vec<(String, ArrayRef)> = Vec::new();
    columns.push(("episode_index".into(), int64_column(rows, |row| row.index)));
    let mut tasks = ListBuilder::new(StringBuilder::new());
    for row in rows {
        for task in &row.tasks {
            tasks.values().append_value(task);
        }
        tasks.append(true);
    }
    columns.push(("tasks".into(), Arc::new(tasks.finish())));
    columns.push(("length".into(), int64_column(rows, |row| row.length)));
    columns.push((
        "data/chunk_index".into(),
        int64_column(rows, |row| row.data.chunk.into()),
    ));
    columns.push((
        "data/file_index".into(),
        int64_column(rows, |row| row.data.file.into()),
    ));
    columns.push((
        "dataset_from_index".into(),
        int64_column(rows, |row| row.from),
    ));
    columns.push(("dataset_to_index".into(), int64_column(rows, |row| row.to)));
    for (video, (key, _, _)) in first.videos.iter().enumerate() {
        let prefix = format!("videos/{key}");
        columns.push((
            format!("{prefix}/chunk_index"),
            int64_column(rows, |row| row.videos[video].1.chunk.into()),
        ));
        columns.push((
            format!("{prefix}/file_index"),
            int64_column(rows, |row| row.videos[video].1.file.into()),
        ));
        columns.push((
            format!("{prefix}/from_timestamp"),
            Arc::new(Float64Array::from(vec![0.0; rows.len()])),
        ));
        columns.push((
            format!("{prefix}/to_timestamp"),
            Arc::new(Float64Array::from_iter_values(
                rows.iter().map(|row| row.videos[video].2),
            )),
        ));
    }
    for (feature, (name, summary, image)) in first.stats.iter().enumerate() {
        for key in summary.values.keys() {
            columns.push((
                format!("stats/{name}/{key}"),
                stat_column(rows, feature, key, *image),
            ));
        }
        let mut count = ListBuilder::new(Int64Builder::new());
        for row in rows {
            let n = row.stats[feature].1.count;
            count
                .values()
                .append_value(i64::try_from(n).unwrap_or(i64::MAX));
            count.append(true);
        }
        columns.push((format!("stats/{name}/count"), Arc::new(count.finish())));
    }
    columns.push((
        "meta/episodes/chunk_index".into(),
        int64_column(rows, |_| 0),
    ));
    columns.push(("meta/episodes/file_index".into(), int64_column(rows, |_| 0)));
    let path = root.join("meta/episodes/chunk-000/file-000.parquet");
    write_table(&path, columns, HashMap::new())
}

/// Writes `meta/tasks.parquet` in `root`: column `task_index`, indexed by `task` (the pandas
/// index LeRobot's `load_tasks` reads, restored from the table's `pandas` metadata).
pub(super) fn write_tasks(root: &Path, tasks: &[String]) -> Result<(), BoxError> {
    let columns: Vec<(String, ArrayRef)> = vec![
        (
            "task_index".into(),
            Arc::new(Int64Array::from_iter_values(0..tasks.len() as i64)),
        ),
        ("task".into(), Arc::new(StringArray::from(tasks.to_vec()))),
    ];
    let pandas = serde_json::json!({
        "index_columns": ["task"],
        "column_indexes": [{
            "name": null, "field_name": null, "pandas_type": "unicode",
            "numpy_type": "object", "metadata": {"encoding": "UTF-8"},
        }],
        "columns": [
            {"name": "task_index", "field_name": "task_index", "pandas_type": "int64",
             "numpy_type": "int64", "metadata": null},
            {"name": "task", "field_name": "task", "pandas_type": "unicode",
             "numpy_type": "object", "metadata": null},
        ],
        "creator": {"library": "yarok", "version": env!("CARGO_PKG_VERSION")},
        "pandas_version": "2.2.3",
    });
    let metadata = HashMap::from([("pandas".to_owned(), pandas.to_string())]);
    write_table(&root.join("meta/tasks.parquet"), columns, metadata)
}
