//! [`DatasetFolder`]: where a dataset is written — beside its folder, then moved into place
//! whole — and the rules that keep a user's files: a folder is replaced only if it holds a
//! dataset yarok wrote and nothing else, and one run at a time writes into it.

use std::collections::BTreeSet;
use std::ffi::OsString;
use std::path::{Component, Path, PathBuf};

use yarok_core::BoxError;

/// The list of the files yarok wrote, inside the dataset (LeRobot reads past it).
const MANIFEST: &str = "meta/yarok_files.json";

/// A dataset folder claimed for one run: locked, its dataset written in `partial` beside it.
#[derive(Debug)]
pub(super) struct DatasetFolder {
    destination: PathBuf,
    partial: PathBuf,
    lock: PathBuf,
    committed: bool,
}

/// `folder`'s sibling `.{name}.yarok-{what}`.
fn beside(folder: &Path, what: &str) -> PathBuf {
    let mut name = OsString::from(".");
    name.push(folder.file_name().unwrap_or_default());
    name.push(format!(".yarok-{what}"));
    folder.with_file_name(name)
}

/// Every file below `root`, as paths relative to it, sorted.
fn files_below(root: &Path) -> Result<BTreeSet<PathBuf>, BoxError> {
    let mut files = BTreeSet::new();
    let mut folders = vec![root.to_owned()];
    while let Some(folder) = folders.pop() {
        let entries = std::fs::read_dir(&folder)
            .map_err(|e| format!("cannot read {}: {e}", folder.display()))?;
        for entry in entries {
            let entry = entry.map_err(|e| format!("cannot read {}: {e}", folder.display()))?;
            let path = entry.path();
            let kind = entry
                .file_type()
                .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
            if kind.is_dir() {
                folders.push(path);
            } else if let Ok(relative) = path.strip_prefix(root) {
                files.insert(relative.to_owned());
            }
        }
    }
    Ok(files)
}

/// The files the manifest of the dataset in `root` lists, if it has one.
fn manifest(root: &Path) -> Result<Option<BTreeSet<PathBuf>>, BoxError> {
    let path = root.join(MANIFEST);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Ok(None);
    };
    let files: Vec<PathBuf> = serde_json::from_str(&text)
        .map_err(|e| format!("{} is not yarok's list of its files: {e}", path.display()))?;
    Ok(Some(files.into_iter().collect()))
}

/// Why `destination` may not receive a dataset, if it may not.
fn refusal(destination: &Path) -> Result<Option<String>, BoxError> {
    let shown = destination.display();
    let Ok(metadata) = std::fs::metadata(destination) else {
        return Ok(None);
    };
    if !metadata.is_dir() {
        return Ok(Some(format!("{shown} is a file, not a folder")));
    }
    let present = files_below(destination)?;
    if present.is_empty() {
        return Ok(None);
    }
    let Some(own) = manifest(destination)? else {
        let info = destination.join("meta/info.json");
        let version = std::fs::read_to_string(&info)
            .ok()
            .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
            .and_then(|info| info["codebase_version"].as_str().map(str::to_owned));
        return Ok(Some(match (info.is_file(), version) {
            (true, Some(version)) => format!(
                "{shown} holds a LeRobot dataset ({version}) that yarok did not write: give a \
                 new or empty folder"
            ),
            _ => format!(
                "{shown} holds files but no dataset yarok wrote: give a new or empty folder"
            ),
        }));
    };
    let foreign: Vec<String> = present
        .difference(&own)
        .map(|path| path.display().to_string())
        .collect();
    if foreign.is_empty() {
        return Ok(None);
    }
    Ok(Some(format!(
        "{shown} holds a dataset yarok wrote, and files it did not ({}{}): move them out, or \
         give another folder",
        foreign[..foreign.len().min(3)].join(", "),
        if foreign.len() > 3 { ", …" } else { "" }
    )))
}

/// Whether process `pid` is alive.
fn alive(pid: u32) -> bool {
    Path::new(&format!("/proc/{pid}")).exists()
}

impl DatasetFolder {
    /// Claims `destination` for this run's dataset: refused when it is no folder of its own
    /// (empty, `.`, `..`, a root), holds anything but a dataset yarok wrote, or another run
    /// writes into it.
    ///
    /// # Errors
    ///
    /// The refusal, naming the folder; or what could not be created.
    pub(super) fn claim(destination: &Path) -> Result<Self, BoxError> {
        let named = matches!(
            destination.components().next_back(),
            Some(Component::Normal(_))
        );
        if destination.as_os_str().is_empty() || !named {
            return Err(format!(
                "the dataset's folder {:?} is no folder of its own: give one such as out/run",
                destination.display().to_string()
            )
            .into());
        }
        if let Some(refused) = refusal(destination)? {
            return Err(refused.into());
        }
        if let Some(parent) = destination.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)
                .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
        }
        let lock = beside(destination, "lock");
        let pid = std::process::id();
        let taken = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&lock);
        if taken.is_err() {
            let holder = std::fs::read_to_string(&lock)
                .ok()
                .and_then(|text| text.trim().parse::<u32>().ok());
            match holder {
                Some(holder) if alive(holder) && holder != pid => {
                    return Err(format!(
                        "another yarok run (process {holder}) is writing a dataset into {}",
                        destination.display()
                    )
                    .into());
                }
                // Left by a run that ended without removing it.
                _ => {}
            }
        }
        std::fs::write(&lock, pid.to_string())
            .map_err(|e| format!("cannot write {}: {e}", lock.display()))?;
        let partial = beside(destination, "partial");
        if partial.exists() {
            // A dataset of a run that was killed, under the lock this run now holds.
            std::fs::remove_dir_all(&partial)
                .map_err(|e| format!("cannot remove {}: {e}", partial.display()))?;
        }
        std::fs::create_dir_all(&partial)
            .map_err(|e| format!("cannot create {}: {e}", partial.display()))?;
        Ok(Self {
            destination: destination.to_owned(),
            partial,
            lock,
            committed: false,
        })
    }

    /// Where the dataset is being written.
    pub(super) fn partial(&self) -> &Path {
        &self.partial
    }

    /// Moves the written dataset into place, with the list of its files; the dataset the folder
    /// held before (only yarok's files) is removed once the new one is there.
    ///
    /// # Errors
    ///
    /// When a file cannot be written or moved, or the folder has changed since it was claimed
    /// (then nothing is replaced and the new dataset is left where it was written, named).
    pub(super) fn commit(mut self) -> Result<(), BoxError> {
        let written: Vec<PathBuf> = files_below(&self.partial)?
            .into_iter()
            .chain([PathBuf::from(MANIFEST)])
            .collect();
        let manifest_path = self.partial.join(MANIFEST);
        let text = serde_json::to_string_pretty(&written)?;
        std::fs::write(&manifest_path, text)
            .map_err(|e| format!("cannot write {}: {e}", manifest_path.display()))?;
        let kept = |reason: String| -> BoxError {
            format!(
                "{reason}; the new dataset is kept in {}",
                self.partial.display()
            )
            .into()
        };
        if let Some(refused) = refusal(&self.destination)? {
            self.committed = true;
            return Err(kept(refused));
        }
        let old = beside(&self.destination, "old");
        let replacing = files_below(&self.destination).is_ok_and(|files| !files.is_empty());
        if replacing {
            std::fs::rename(&self.destination, &old).map_err(|e| {
                kept(format!(
                    "cannot move {} aside: {e}",
                    self.destination.display()
                ))
            })?;
        }
        if let Err(error) = std::fs::rename(&self.partial, &self.destination) {
            if replacing {
                let _back = std::fs::rename(&old, &self.destination);
            }
            self.committed = true;
            return Err(kept(format!(
                "cannot move the dataset into {}: {error}",
                self.destination.display()
            )));
        }
        self.committed = true;
        if replacing {
            remove_own(&old)?;
        }
        Ok(())
    }
}

/// Removes the dataset yarok wrote in `folder`: the files its manifest lists, then the folders
/// left empty; anything else stays, and is named.
fn remove_own(folder: &Path) -> Result<(), BoxError> {
    let own = manifest(folder)?.unwrap_or_default();
    for file in &own {
        let path = folder.join(file);
        if path.is_file() {
            std::fs::remove_file(&path)
                .map_err(|e| format!("cannot remove {}: {e}", path.display()))?;
        }
    }
    let mut folders = vec![folder.to_owned()];
    let mut all = Vec::new();
    while let Some(next) = folders.pop() {
        all.push(next.clone());
        if let Ok(entries) = std::fs::read_dir(&next) {
            folders.extend(entries.flatten().map(|e| e.path()).filter(|p| p.is_dir()));
        }
    }
    for empty in all.iter().rev() {
        let _not_empty = std::fs::remove_dir(empty);
    }
    if folder.exists() {
        return Err(format!(
            "the dataset replaced held files yarok did not write; they are kept in {}",
            folder.display()
        )
        .into());
    }
    Ok(())
}

impl Drop for DatasetFolder {
    fn drop(&mut self) {
        if !self.committed {
            let _incomplete = std::fs::remove_dir_all(&self.partial);
        }
        let _released = std::fs::remove_file(&self.lock);
    }
}
