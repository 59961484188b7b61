//! [`OutputLock`]: one writer at a time per output. A writer takes the lock of its output (a
//! file or a dataset's folder) before it writes, and holds it until it is done, so that a
//! second run writing the same path is refused naming the first instead of interleaving
//! with it.

use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::OutputError;
use crate::output_file::create_new;

/// `output`'s sibling `.{name}.yarok-{what}`: where its lock (`lock`) or a writer's
/// unfinished work (`partial`) goes.
pub fn beside(output: &Path, what: &str) -> PathBuf {
    let mut name = OsString::from(".");
    name.push(output.file_name().unwrap_or_default());
    name.push(format!(".yarok-{what}"));
    output.with_file_name(name)
}

/// The lock of one output, held by this process until dropped: a file beside the output
/// (`.NAME.yarok-lock`) created anew, never through a link nor over a file, holding the
/// process id.
///
/// # Examples
///
/// ```
/// use yarok_core::output_lock::OutputLock;
///
/// let folder = tempfile::tempdir()?;
/// let recording = folder.path().join("run.mcap");
/// let held = OutputLock::take(&recording, "the recording run.mcap")?;
/// assert!(folder.path().join(".run.mcap.yarok-lock").is_file());
/// drop(held);
/// assert!(!folder.path().join(".run.mcap.yarok-lock").exists());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct OutputLock {
    path: PathBuf,
}

impl OutputLock {
    /// Takes the lock of `output`, which a refusal describes as `what` (`a dataset into
    /// out/run`). A lock left by a run that ended (its process is gone) is taken over.
    ///
    /// # Errors
    ///
    /// When a live run holds it (naming its process), when a file, folder or link of the
    /// user's is at the lock's name (never written through, never removed), or when it cannot
    /// be created.
    pub fn take(output: &Path, what: &str) -> Result<Self, OutputError> {
        let path = beside(output, "lock");
        let failed = |action, source| OutputError::LockFailed {
            action,
            lock: path.clone(),
            source,
        };
        let pid = std::process::id();
        for _attempt in 0..2 {
            let created = create_new(&path);
            let error = match created {
                Ok(mut file) => {
                    let lock = Self { path: path.clone() };
                    file.write_all(pid.to_string().as_bytes())
                        .map_err(|source| failed("write", source))?;
                    return Ok(lock);
                }
                Err(error) => error,
            };
            if error.kind() != std::io::ErrorKind::AlreadyExists {
                return Err(failed("create", error));
            }
            let in_the_way = || OutputError::LockInTheWay {
                lock: path.clone(),
                output: output.to_path_buf(),
            };
            if !std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
                return Err(in_the_way());
            }
            let text = crate::bounded::read_text(&path, 32).map_err(|_| in_the_way())?;
            match text.trim().parse::<u32>() {
                Ok(holder) if holder != pid && alive(holder) => {
                    return Err(OutputError::Locked {
                        what: what.to_owned(),
                        pid: holder,
                    });
                }
                // Left by a run that ended without removing it.
                Ok(_) => std::fs::remove_file(&path).map_err(|source| {
                    failed("remove the lock left by a run that ended,", source)
                })?,
                Err(_) if text.is_empty() => {
                    return Err(OutputError::LockStarting {
                        what: what.to_owned(),
                        lock: path.clone(),
                    });
                }
                Err(_) => return Err(in_the_way()),
            }
        }
        Err(OutputError::LockRace { lock: path })
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        let _released = std::fs::remove_file(&self.path);
    }
}

/// Whether process `pid` is alive.
fn alive(pid: u32) -> bool {
    Path::new(&format!("/proc/{pid}")).exists()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_writer_is_refused_naming_the_first_until_it_is_done() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("run.mcap");
        let first = OutputLock::take(&output, "run.mcap").unwrap();
        std::fs::write(beside(&output, "lock"), "1").unwrap();
        let refused = OutputLock::take(&output, "run.mcap").unwrap_err();
        assert_eq!(
            refused.to_string(),
            "another yarok run (process 1) is writing run.mcap"
        );
        drop(first);
        let second = OutputLock::take(&output, "run.mcap").unwrap();
        drop(second);
    }

    #[test]
    fn a_link_or_a_users_file_at_the_locks_name_is_refused_and_left() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("run.mcap");
        let key = folder.path().join("id_rsa");
        std::fs::write(&key, "a user's key").unwrap();
        std::os::unix::fs::symlink(&key, beside(&output, "lock")).unwrap();
        let refused = OutputLock::take(&output, "run.mcap").unwrap_err();
        assert!(
            matches!(refused, OutputError::LockInTheWay { .. }),
            "{refused}"
        );
        assert_eq!(std::fs::read_to_string(&key).unwrap(), "a user's key");
        std::fs::remove_file(beside(&output, "lock")).unwrap();
        std::fs::write(beside(&output, "lock"), "a user's notes").unwrap();
        assert!(OutputLock::take(&output, "run.mcap").is_err());
        assert_eq!(
            std::fs::read_to_string(beside(&output, "lock")).unwrap(),
            "a user's notes"
        );
    }
}
