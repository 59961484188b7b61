//! Output files: yarok replaces a file only when it wrote it.
//!
//! Every writer (a recording, a video, a CSV, an image, a calibration) checks its path with
//! [`check_replaceable`] before it creates the file, giving a recogniser that reads whether an
//! existing file is one yarok wrote (a mark in the file's own format: an MCAP header's library,
//! a PNG's `Software` text, an MP4's comment). A user's file at that path is refused, never
//! truncated.

use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
use std::path::Path;

use crate::OutputError;

/// Reads whether the existing regular file at a path is one yarok wrote, from its content.
pub type Recogniser = fn(&Path) -> std::io::Result<bool>;

/// Checks that `path` may be written as a `kind` (an "MCAP recording"): nothing is there yet,
/// or a character device (`/dev/null`, a terminal), or a named pipe that a reader has open, or
/// a regular file `wrote` recognises as yarok's. Links are judged by what they point to.
///
/// # Errors
///
/// An empty path, a folder, a disk (a block device), a socket, a named pipe nobody reads
/// (writing would wait forever), or a regular file yarok did not write (or that cannot be
/// read), naming the path and what to do.
///
/// # Examples
///
/// ```
/// use yarok_core::output::check_replaceable;
///
/// fn starts_with_our_mark(path: &std::path::Path) -> std::io::Result<bool> {
///     Ok(std::fs::read(path)?.starts_with(b"written by yarok"))
/// }
///
/// let folder = std::env::temp_dir().join(format!("yarok-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&folder)?;
/// let notes = folder.join("notes.txt");
/// std::fs::write(&notes, "a user's notes")?;
/// let refused = check_replaceable(&notes, "note", starts_with_our_mark).unwrap_err();
/// assert!(matches!(refused, yarok_core::OutputError::NotYaroks { .. }));
/// assert!(refused.to_string().contains("notes.txt"));
/// std::fs::write(&notes, "written by yarok: 3 notes")?;
/// assert!(check_replaceable(&notes, "note", starts_with_our_mark).is_ok());
/// assert!(check_replaceable(&folder.join("new.txt"), "note", starts_with_our_mark).is_ok());
/// # std::fs::remove_dir_all(&folder)?;
/// # Ok::<(), std::io::Error>(())
/// ```
pub fn check_replaceable(path: &Path, kind: &str, wrote: Recogniser) -> Result<(), OutputError> {
    let path_buf = || path.to_path_buf();
    let kind_text = || kind.to_owned();
    if path.as_os_str().is_empty() {
        return Err(OutputError::EmptyPath { kind: kind_text() });
    }
    let metadata = match std::fs::metadata(path) {
        Ok(metadata) => metadata,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(source) => {
            return Err(OutputError::Inaccessible {
                path: path_buf(),
                source,
            });
        }
    };
    if metadata.is_dir() {
        return Err(OutputError::Folder {
            path: path_buf(),
            kind: kind_text(),
        });
    }
    let file_type = metadata.file_type();
    if file_type.is_block_device() {
        return Err(OutputError::BlockDevice {
            path: path_buf(),
            kind: kind_text(),
        });
    }
    if file_type.is_socket() {
        return Err(OutputError::Socket {
            path: path_buf(),
            kind: kind_text(),
        });
    }
    if file_type.is_fifo() {
        return has_a_reader(path).map_err(|source| OutputError::PipeWithoutReader {
            path: path_buf(),
            kind: kind_text(),
            source,
        });
    }
    if !metadata.is_file() {
        return Ok(());
    }
    match wrote(path) {
        Ok(true) => Ok(()),
        Ok(false) => Err(OutputError::NotYaroks {
            path: path_buf(),
            kind: kind_text(),
        }),
        Err(source) => Err(OutputError::Unreadable {
            path: path_buf(),
            kind: kind_text(),
            source,
        }),
    }
}

/// Whether the named pipe at `path` has a reader: opening it to write without blocking
/// succeeds only then.
fn has_a_reader(path: &Path) -> std::io::Result<()> {
    std::fs::OpenOptions::new()
        .write(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map(drop)
}

/// The first `limit` bytes of `path` (fewer if it is shorter): enough for a recogniser to read
/// a header without reading a whole recording.
///
/// # Errors
///
/// When the file cannot be opened or read.
pub fn head(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(limit)
        .read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// Makes the folder `path` goes in (and its parents), as a writer does before it creates the
/// file: an output may name a folder that does not exist yet.
///
/// # Errors
///
/// When a folder cannot be made, naming it.
pub fn make_folder_for(path: &Path) -> Result<(), OutputError> {
    match path
        .parent()
        .filter(|folder| !folder.as_os_str().is_empty())
    {
        Some(folder) => std::fs::create_dir_all(folder).map_err(|source| OutputError::Folderless {
            folder: folder.to_path_buf(),
            source,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn never(_: &Path) -> std::io::Result<bool> {
        Ok(false)
    }

    #[test]
    fn a_named_pipe_is_written_only_while_a_reader_has_it_open() {
        let folder = tempfile::tempdir().unwrap();
        let pipe = folder.path().join("pipe");
        let made = std::process::Command::new("mkfifo")
            .arg(&pipe)
            .status()
            .unwrap();
        assert!(made.success());
        let refused = check_replaceable(&pipe, "video", never)
            .unwrap_err()
            .to_string();
        assert!(
            refused.contains("is a named pipe nobody reads")
                && refused.contains("start its reader"),
            "{refused}"
        );
        let reader = std::fs::OpenOptions::new()
            .read(true)
            .custom_flags(libc::O_NONBLOCK)
            .open(&pipe)
            .unwrap();
        assert!(check_replaceable(&pipe, "video", never).is_ok());
        drop(reader);
    }

    #[test]
    fn a_character_device_is_written_and_a_socket_is_not() {
        assert!(check_replaceable(Path::new("/dev/null"), "video", never).is_ok());
        let folder = tempfile::tempdir().unwrap();
        let socket = folder.path().join("socket");
        let _listening = std::os::unix::net::UnixListener::bind(&socket).unwrap();
        let refused = check_replaceable(&socket, "video", never).unwrap_err();
        assert!(matches!(refused, OutputError::Socket { .. }), "{refused}");
    }
}
