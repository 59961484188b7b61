//! [`DatasetFolder`]: where a dataset is written — beside its folder, then moved into place
//! whole — and the rules that keep a user's files: a folder is replaced only if it holds a
//! dataset yarok wrote and nothing else, and one run at a time writes into it.

use std::collections::BTreeSet;
use std::path::{Component, Path, PathBuf};

use yarok_core::BoxError;
use yarok_core::output_file::write_in_own_folder;
use yarok_core::output_lock::{OutputLock, beside};

/// The list of the files yarok wrote, inside the dataset (LeRobot reads past it).
const MANIFEST: &str = "meta/yarok_files.json";

/// A dataset folder claimed for one run: locked, its dataset written in `partial` beside it.
#[derive(Debug)]
pub(super) struct DatasetFolder {
    destination: PathBuf,
    partial: PathBuf,
    _lock: OutputLock,
    committed: bool,
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

/// The files the manifest of the dataset in `root` lists, if it has one: each a relative
/// path inside the dataset that reaches its file through real folders, never through a link.
///
/// # Errors
///
/// When the manifest is not yarok's list, or an entry leaves the dataset (an absolute path,
/// `..`, a link on the way): the entry is named, and nothing may be removed on its word.
fn manifest(root: &Path) -> Result<Option<BTreeSet<PathBuf>>, BoxError> {
    let path = root.join(MANIFEST);
    if !std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
        return Ok(None);
    }
    let text = yarok_core::bounded::read_text(&path, yarok_core::bounded::CONFIG_LIMIT)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let files: Vec<PathBuf> = serde_json::from_str(&text)
        .map_err(|e| format!("{} is not yarok's list of its files: {e}", path.display()))?;
    for file in &files {
        if let Some(why) = outside(root, file) {
            return Err(format!(
                "{} lists {:?}, which {why}: yarok trusts its list only for files inside the \
                 dataset, and removes nothing on its word; remove the entry, or give another \
                 folder",
                path.display(),
                file.display().to_string()
            )
            .into());
        }
    }
    Ok(Some(files.into_iter().collect()))
}

/// Why the manifest entry `file` does not name a file inside the dataset at `root`, if it
/// does not: it is not a plain relative path, or a folder on its way is a link (or no folder).
fn outside(root: &Path, file: &Path) -> Option<&'static str> {
    let plain = file
        .components()
        .all(|component| matches!(component, Component::Normal(_)));
    if file.as_os_str().is_empty() || !plain {
        return Some("is not a path inside the dataset");
    }
    let mut reached = root.to_owned();
    let parts: Vec<_> = file.components().collect();
    for part in &parts[..parts.len() - 1] {
        reached.push(part);
        match std::fs::symlink_metadata(&reached) {
            Ok(metadata) if metadata.file_type().is_symlink() => {
                return Some("goes through a link out of the dataset");
            }
            Ok(metadata) if !metadata.is_dir() => return Some("goes through a file"),
            _ => {}
        }
    }
    None
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

/// The file in a dataset being written that says a yarok run made its folder (its process
/// id): a leftover holding it is a killed run's, and may be removed.
const PARTIAL_MARK: &str = ".yarok-partial";

/// Removes the dataset a killed run left at `partial` (it holds [`PARTIAL_MARK`]); anything
/// else there is the user's, and is refused.
fn remove_leftover(partial: &Path) -> Result<(), BoxError> {
    let shown = partial.display();
    match std::fs::symlink_metadata(partial) {
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Ok(metadata)
            if metadata.is_dir()
                && std::fs::symlink_metadata(partial.join(PARTIAL_MARK))
                    .is_ok_and(|m| m.is_file()) =>
        {
            std::fs::remove_dir_all(partial)
                .map_err(|e| format!("cannot remove {shown}, left by a run that ended: {e}").into())
        }
        _ => Err(format!(
            "{shown} is in the way of the dataset being written, and is not a leftover of a \
             yarok run: move it away, or give another folder"
        )
        .into()),
    }
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
        let lock = OutputLock::take(
            destination,
            &format!("a dataset into {}", destination.display()),
        )?;
        let partial = beside(destination, "partial");
        remove_leftover(&partial)?;
        std::fs::create_dir(&partial)
            .and_then(|()| {
                write_in_own_folder(
                    &partial.join(PARTIAL_MARK),
                    std::process::id().to_string().as_bytes(),
                )
            })
            .map_err(|e| format!("cannot create {}: {e}", partial.display()))?;
        Ok(Self {
            destination: destination.to_owned(),
            partial,
            _lock: lock,
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
        let mark = self.partial.join(PARTIAL_MARK);
        std::fs::remove_file(&mark)
            .map_err(|e| format!("cannot remove {}: {e}", mark.display()))?;
        let written: Vec<PathBuf> = files_below(&self.partial)?
            .into_iter()
            .chain([PathBuf::from(MANIFEST)])
            .collect();
        let manifest_path = self.partial.join(MANIFEST);
        let text = serde_json::to_string_pretty(&written)?;
        write_in_own_folder(&manifest_path, text.as_bytes())
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
        // A file, or a link itself (never what it points to).
        let removable = std::fs::symlink_metadata(&path)
            .is_ok_and(|m| m.is_file() || m.file_type().is_symlink());
        if removable && outside(folder, file).is_none() {
            std::fs::remove_file(&path)
                .map_err(|e| format!("cannot remove {}: {e}", path.display()))?;
        }
    }
    let mut folders = vec![folder.to_owned()];
    let mut all = Vec::new();
    while let Some(next) = folders.pop() {
        all.push(next.clone());
        if let Ok(entries) = std::fs::read_dir(&next) {
            // A DirEntry's type is the link's own: links to folders are not walked into.
            let real_folders = entries
                .flatten()
                .filter(|e| e.file_type().is_ok_and(|kind| kind.is_dir()))
                .map(|e| e.path());
            folders.extend(real_folders);
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
    }
}
