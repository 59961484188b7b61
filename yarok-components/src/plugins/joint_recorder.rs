//! [`JointRecorder`]: every joint's position and velocity, one CSV row per tick.

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use yarok_core::BoxError;
use yarok_core::output_file::OutputFile;
use yarok_core::runtime::{Plugin, World};
use yarok_mjc::{Data, JointId};

/// Where and how often a [`JointRecorder`] writes (`[plugins.joints_csv]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default)]
pub struct JointRecorderSettings {
    /// The CSV file (created, with its folder, at start; a file there is replaced only if it
    /// is a joints CSV yarok wrote).
    pub path: PathBuf,
    /// Write a row every this many ticks.
    pub every: u64,
}

impl Default for JointRecorderSettings {
    fn default() -> Self {
        Self {
            path: PathBuf::from("joints.csv"),
            every: 1,
        }
    }
}

/// Records every joint's position and velocity in `sim`, one CSV row per tick (or every
/// `every` ticks): `time`, then for each joint in the model's order `<name>.pos`, `<name>.vel`
/// (`<name>.pos[k]` for joints with several coordinates), numbers in their shortest exact form.
///
/// Registered by `yarok::platform()` as `joints_csv`:
///
/// ```toml
/// [plugins.joints_csv]
/// path = "run.csv"
/// ```
#[derive(Debug)]
pub struct JointRecorder {
    settings: JointRecorderSettings,
    file: Option<BufWriter<OutputFile>>,
    joints: Vec<JointId>,
    row: String,
}

impl JointRecorder {
    /// A recorder with these settings; the file is created when the run starts.
    ///
    /// # Errors
    ///
    /// When `every` is 0.
    pub fn new(settings: JointRecorderSettings) -> Result<Self, BoxError> {
        if settings.every == 0 {
            return Err("`every` must be at least 1 tick".into());
        }
        Ok(Self {
            settings,
            file: None,
            joints: Vec::new(),
            row: String::new(),
        })
    }

    fn header(&self, data: &Data) -> String {
        let model = data.model();
        let mut header = String::from("time");
        for (index, joint) in self.joints.iter().enumerate() {
            let name = model
                .joint_name(*joint)
                .unwrap_or_else(|| format!("joint{index}"));
            for (what, count) in [
                ("pos", data.qpos(*joint).len()),
                ("vel", data.qvel(*joint).len()),
            ] {
                for k in 0..count {
                    header.push(',');
                    header.push_str(&name);
                    header.push('.');
                    header.push_str(what);
                    if count > 1 {
                        header.push_str(&format!("[{k}]"));
                    }
                }
            }
        }
        header
    }
}

/// Whether the file at `path` is a joints CSV yarok wrote: its header is `time` and then only
/// joints' `.pos` and `.vel` columns (`arm/joint1.pos`, `free.pos[3]`).
fn joints_csv_by_yarok(path: &std::path::Path) -> std::io::Result<bool> {
    let head = yarok_core::output::head(path, 1 << 20)?;
    let Some(header) = head.split(|b| *b == b'\n').next() else {
        return Ok(false);
    };
    let Ok(header) = std::str::from_utf8(header) else {
        return Ok(false);
    };
    let mut columns = header.split(',');
    let joint_column = |column: &str| {
        let column = column.split_once('[').map_or(column, |(name, index)| {
            if index
                .strip_suffix(']')
                .is_some_and(|k| k.parse::<usize>().is_ok())
            {
                name
            } else {
                ""
            }
        });
        column
            .rsplit_once('.')
            .is_some_and(|(joint, what)| !joint.is_empty() && (what == "pos" || what == "vel"))
    };
    Ok(columns.next() == Some("time") && columns.all(joint_column))
}

impl Plugin for JointRecorder {
    fn writes(&self) -> Vec<std::path::PathBuf> {
        vec![self.settings.path.clone()]
    }

    fn name(&self) -> String {
        format!("joints_csv ({})", self.settings.path.display())
    }

    fn environments(&self) -> Vec<&'static str> {
        super::only_sim()
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let sim = super::sim_backend(world)?;
        self.joints = sim.model().joints().collect();
        let path = &self.settings.path;
        let mut file = BufWriter::new(OutputFile::create(path, "joints CSV", joints_csv_by_yarok)?);
        writeln!(file, "{}", self.header(&sim.data()))?;
        self.file = Some(file);
        Ok(())
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let tick = world.pl().ticks();
        let Some(file) = &mut self.file else {
            return Ok(());
        };
        if !tick.is_multiple_of(self.settings.every) {
            return Ok(());
        }
        let data = super::sim_backend(world)?.data();
        self.row.clear();
        self.row.push_str(&data.time().to_string());
        for joint in &self.joints {
            for value in data.qpos(*joint).iter().chain(data.qvel(*joint)) {
                self.row.push(',');
                self.row.push_str(&value.to_string());
            }
        }
        writeln!(file, "{}", self.row)?;
        Ok(())
    }

    fn end(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        if let Some(file) = self.file.take() {
            file.into_inner()
                .map_err(|e| format!("cannot write {}: {e}", self.settings.path.display()))?
                .commit()?;
        }
        Ok(())
    }
}
