//! Output files: yarok replaces a file only when it wrote it.
//!
//! Every writer (a recording, a video, a CSV, an image, a calibration) checks its path with
//! [`check_replaceable`] before it creates the file, giving a recogniser that reads whether an
//! existing file is one yarok wrote (a mark in the file's own format: an MCAP header's library,
//! a PNG's `Software` text, an MP4's comment). A user's file at that path is refused, never
//! truncated.

use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
use std::path::Path;

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
/// assert!(refused.contains("notes.txt") && refused.contains("did not write"));
/// std::fs::write(&notes, "written by yarok: 3 notes")?;
/// assert!(check_replaceable(&notes, "note", starts_with_our_mark).is_ok());
/// assert!(check_replaceable(&folder.join("new.txt"), "note", starts_with_our_mark).is_ok());
/// # std::fs::remove_dir_all(&folder)?;
/// # Ok::<(), std::io::Error>(())
/// ```
pub fn check_replaceable(path: &Path, kind: &str, wrote: Recogniser) -> Result<(), String> {
    let shown = path.display();
    if path.as_os_str().is_empty() {
        return Err(format!("the {kind}'s path is empty: give a file's path"));
    }
    let metadata = match std::fs::metadata(path) {
        Ok(metadata) => metadata,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(error) => return Err(format!("cannot look at {shown} ({error})")),
    };
    if metadata.is_dir() {
        return Err(format!(
            "{shown} is a folder: give a file's path for the {kind}"
        ));
    }
    let file_type = metadata.file_type();
    if file_type.is_block_device() {
        return Err(format!(
            "{shown} is a disk (a block device): yarok does not write a {kind} over a disk; give \
             a file's path"
        ));
    }
    if file_type.is_socket() {
        return Err(format!(
            "{shown} is a socket: give a file's path for the {kind}"
        ));
    }
    if file_type.is_fifo() {
        return has_a_reader(path).map_err(|error| {
            format!(
                "{shown} is a named pipe nobody reads ({error}): writing the {kind} would wait \
                 forever; start its reader first, or give a file's path"
            )
        });
    }
    if !metadata.is_file() {
        return Ok(());
    }
    match wrote(path) {
        Ok(true) => Ok(()),
        Ok(false) => Err(format!(
            "{shown} exists and is not a {kind} yarok wrote: yarok does not replace a file it \
             did not write; move it away or give another path"
        )),
        Err(error) => Err(format!(
            "{shown} exists and cannot be read ({error}), so yarok cannot tell it wrote it: \
             it is left as it is; move it away or give another path"
        )),
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
pub fn make_folder_for(path: &Path) -> Result<(), String> {
    match path
        .parent()
        .filter(|folder| !folder.as_os_str().is_empty())
    {
        Some(folder) => std::fs::create_dir_all(folder)
            .map_err(|e| format!("cannot make the folder {} ({e})", folder.display())),
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
        let refused = check_replaceable(&pipe, "video", never).unwrap_err();
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
        assert_eq!(check_replaceable(&pipe, "video", never), Ok(()));
        drop(reader);
    }

    #[test]
    fn a_character_device_is_written_and_a_socket_is_not() {
        assert_eq!(
            check_replaceable(Path::new("/dev/null"), "video", never),
            Ok(())
        );
        let folder = tempfile::tempdir().unwrap();
        let socket = folder.path().join("socket");
        let _listening = std::os::unix::net::UnixListener::bind(&socket).unwrap();
        let refused = check_replaceable(&socket, "video", never).unwrap_err();
        assert!(refused.contains("is a socket"), "{refused}");
    }
}
