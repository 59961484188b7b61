//! [`OutputFile`]: the one way yarok's library writes a file at a path a user gave.

use std::fs::File;
use std::io::Write;
use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::OutputError;
use crate::output::{Recogniser, check_replaceable, make_folder_for};

/// A file yarok writes at a path a user gave (a recording, an image, a CSV, a calibration).
///
/// [`OutputFile::create`] checks the path ([`check_replaceable`]: nothing there, or a file
/// yarok wrote), makes its folder, and opens a file of its own beside it, created new
/// ([`create_new`]: never an existing file, never through a link).
/// [`OutputFile::commit`] puts it at the path in one step (a rename): a reader never sees a
/// half-written file; a link planted at the path in the meantime is replaced, never written
/// through; a file that appeared there in the meantime is left as it is (the output is kept
/// beside it, named in the error). Dropped without a commit, the file of its own is removed
/// and the path is as it was. A device the user named (`/dev/null`, a terminal, a named
/// pipe a reader has open) is written directly.
///
/// # Examples
///
/// ```
/// use std::io::Write;
/// use yarok_core::output_file::OutputFile;
///
/// fn ours(path: &std::path::Path) -> std::io::Result<bool> {
///     Ok(std::fs::read(path)?.starts_with(b"yarok"))
/// }
///
/// let folder = std::env::temp_dir().join(format!("yarok-output-doc-{}", std::process::id()));
/// let path = folder.join("runs/log.txt");
/// let mut file = OutputFile::create(&path, "log", ours)?;
/// file.write_all(b"yarok log\n")?;
/// assert!(!path.exists()); // nothing at the path until the commit
/// file.commit()?;
/// assert_eq!(std::fs::read(&path)?, b"yarok log\n");
/// # std::fs::remove_dir_all(&folder)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct OutputFile {
    path: PathBuf,
    kind: String,
    wrote: Recogniser,
    file: File,
    /// Where it is written until the commit; `None` for a device written directly.
    beside: Option<PathBuf>,
    /// Whether a file yarok wrote was at the path when it was created.
    replaces: bool,
}

/// Distinguishes the files of one process written at the same time.
static NEXT: AtomicU64 = AtomicU64::new(0);

impl OutputFile {
    /// Opens the output `path`, a `kind` ("video") whose existing files `wrote` recognises.
    ///
    /// # Errors
    ///
    /// What [`check_replaceable`] and [`make_folder_for`] refuse, or the file beside it
    /// cannot be created ([`OutputError::Unwritable`]).
    pub fn create(path: &Path, kind: &str, wrote: Recogniser) -> Result<Self, OutputError> {
        check_replaceable(path, kind, wrote)?;
        make_folder_for(path)?;
        let unwritable = |source| OutputError::Unwritable {
            path: path.to_path_buf(),
            source,
        };
        let existing = std::fs::metadata(path).ok();
        let device = existing.as_ref().is_some_and(|metadata| {
            let file_type = metadata.file_type();
            file_type.is_char_device() || file_type.is_fifo()
        });
        if device {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(unwritable)?;
            return Ok(Self::new(path, kind, wrote, file, None, false));
        }
        let replaces = std::fs::symlink_metadata(path).is_ok();
        let beside = beside(path);
        let file = create_new(&beside).map_err(unwritable)?;
        Ok(Self::new(path, kind, wrote, file, Some(beside), replaces))
    }

    fn new(
        path: &Path,
        kind: &str,
        wrote: Recogniser,
        file: File,
        beside: Option<PathBuf>,
        replaces: bool,
    ) -> Self {
        Self {
            path: path.to_path_buf(),
            kind: kind.to_owned(),
            wrote,
            file,
            beside,
            replaces,
        }
    }

    /// Where the output is written until its commit (the path itself for a device): what a
    /// program that writes the output by name (an encoder) is given.
    pub fn writing_path(&self) -> &Path {
        self.beside.as_deref().unwrap_or(&self.path)
    }

    /// Puts the written file at its path: flushed to the disk, then renamed onto the path in
    /// one step.
    ///
    /// # Errors
    ///
    /// When it cannot be flushed or renamed ([`OutputError::Unwritable`]), or a file yarok did
    /// not write appeared at the path meanwhile ([`OutputError::Appeared`]: the output is kept
    /// beside it, under the name the error gives).
    pub fn commit(mut self) -> Result<(), OutputError> {
        let unwritable = |source| OutputError::Unwritable {
            path: self.path.clone(),
            source,
        };
        self.file.flush().map_err(unwritable)?;
        let Some(beside) = self.beside.take() else {
            return Ok(());
        };
        self.file.sync_all().map_err(unwritable)?;
        let appeared = |path: &Path| OutputError::Appeared {
            path: path.to_path_buf(),
            kept: beside.clone(),
        };
        if self.replaces {
            // What is there is judged again: a user's file put in its place meanwhile is kept.
            check_replaceable(&self.path, &self.kind, self.wrote)
                .map_err(|_| appeared(&self.path))?;
            std::fs::rename(&beside, &self.path).map_err(unwritable)
        } else {
            // A link never replaces what is at its name, whatever it is (a file, a link).
            match std::fs::hard_link(&beside, &self.path) {
                Ok(()) => std::fs::remove_file(&beside).map_err(unwritable),
                Err(error) if error.kind() == std::io::ErrorKind::AlreadyExists => {
                    Err(appeared(&self.path))
                }
                Err(source) => {
                    let _ = std::fs::remove_file(&beside);
                    Err(OutputError::Unwritable {
                        path: self.path.clone(),
                        source,
                    })
                }
            }
        }
    }
}

impl Write for OutputFile {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.file.write(bytes)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

impl std::io::Seek for OutputFile {
    fn seek(&mut self, position: std::io::SeekFrom) -> std::io::Result<u64> {
        self.file.seek(position)
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        if let Some(beside) = self.beside.take() {
            let _ = std::fs::remove_file(beside);
        }
    }
}

/// Where the output `path` is written until its commit: a hidden name of this process's own
/// beside it.
fn beside(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|name| name.to_string_lossy().into_owned())
        .unwrap_or_default();
    let number = NEXT.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(
        ".{name}.{}-{number}.yarok-writing",
        std::process::id()
    ))
}

/// Creates `path` as a new file, refused if anything is at that name already — a file, a
/// folder, a link (`O_CREAT | O_EXCL` never follows one): how outputs' files and locks are
/// created.
///
/// # Errors
///
/// When something is at `path` ([`std::io::ErrorKind::AlreadyExists`]) or it cannot be
/// created.
#[allow(
    clippy::disallowed_methods,
    reason = "the one place yarok creates a file new"
)]
pub fn create_new(path: &Path) -> std::io::Result<File> {
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
}

/// Writes `bytes` as the output `path` ([`OutputFile`]: checked, written beside it, renamed
/// into place).
///
/// # Errors
///
/// As [`OutputFile::create`], [`OutputFile::commit`], or the bytes cannot be written.
pub fn write_output(
    path: &Path,
    kind: &str,
    wrote: Recogniser,
    bytes: &[u8],
) -> Result<(), OutputError> {
    let mut file = OutputFile::create(path, kind, wrote)?;
    file.write_all(bytes)
        .map_err(|source| OutputError::Unwritable {
            path: path.to_path_buf(),
            source,
        })?;
    file.commit()
}

/// Opens `path`, a file in a folder yarok made for this run (a dataset being written, before
/// it is moved into place), created or emptied, its folder made: never written through a link.
///
/// # Errors
///
/// When the folder or the file cannot be made, or a link is at `path`.
#[allow(
    clippy::disallowed_methods,
    reason = "a folder yarok made for the run holds no user's file"
)]
pub fn file_in_own_folder(path: &Path) -> std::io::Result<File> {
    if let Some(folder) = path.parent() {
        std::fs::create_dir_all(folder)?;
    }
    std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(true)
        .custom_flags(libc::O_NOFOLLOW)
        .open(path)
}

/// Writes `bytes` as `path`, a file in a folder yarok made for this run
/// ([`file_in_own_folder`]).
///
/// # Errors
///
/// As [`file_in_own_folder`], or the bytes cannot be written.
pub fn write_in_own_folder(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    file_in_own_folder(path)?.write_all(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ours(path: &Path) -> std::io::Result<bool> {
        Ok(std::fs::read(path)?.starts_with(b"yarok"))
    }

    #[test]
    fn a_link_planted_before_the_commit_is_not_written_through() {
        let folder = tempfile::tempdir().unwrap();
        let users = folder.path().join("users.txt");
        std::fs::write(&users, "a user's notes").unwrap();
        let output = folder.path().join("out.txt");
        let mut file = OutputFile::create(&output, "log", ours).unwrap();
        file.write_all(b"yarok log").unwrap();
        std::os::unix::fs::symlink(&users, &output).unwrap();
        let refused = file.commit().unwrap_err();
        assert!(matches!(refused, OutputError::Appeared { .. }), "{refused}");
        assert_eq!(std::fs::read(&users).unwrap(), b"a user's notes");
        let OutputError::Appeared { kept, .. } = refused else {
            unreachable!()
        };
        assert_eq!(std::fs::read(kept).unwrap(), b"yarok log");
    }

    #[test]
    fn a_users_file_put_in_the_place_of_yaroks_meanwhile_is_kept() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("out.txt");
        std::fs::write(&output, "yarok, an earlier run").unwrap();
        let mut file = OutputFile::create(&output, "log", ours).unwrap();
        file.write_all(b"yarok log").unwrap();
        std::fs::write(&output, "a user's notes").unwrap();
        assert!(matches!(file.commit(), Err(OutputError::Appeared { .. })));
        assert_eq!(std::fs::read(&output).unwrap(), b"a user's notes");
    }

    #[test]
    fn a_file_dropped_uncommitted_leaves_the_path_as_it_was() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("out.txt");
        std::fs::write(&output, "yarok, an earlier run").unwrap();
        let mut file = OutputFile::create(&output, "log", ours).unwrap();
        file.write_all(b"yarok, half").unwrap();
        drop(file);
        assert_eq!(std::fs::read(&output).unwrap(), b"yarok, an earlier run");
        assert_eq!(std::fs::read_dir(folder.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_device_is_written_directly() {
        let mut file = OutputFile::create(Path::new("/dev/null"), "log", ours).unwrap();
        file.write_all(b"yarok log").unwrap();
        file.commit().unwrap();
    }
}
