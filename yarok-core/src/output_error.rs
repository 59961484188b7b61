//! [`OutputError`]: why yarok does not write an output where it was asked to — every refusal
//! names the path and what to do, and none of them has touched a byte of what is there.

use std::path::PathBuf;

/// Why an output (a recording, a video, a CSV, an image, a calibration, a dataset) is not
/// written: from [`check_replaceable`](crate::output::check_replaceable),
/// [`make_folder_for`](crate::output::make_folder_for), [`OutputFile`](crate::output_file::OutputFile) and
/// [`OutputLock::take`](crate::output_lock::OutputLock::take). `kind` names what was to be
/// written ("video"), `path` where.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// The path is empty.
    #[error("the {kind}'s path is empty: give a file's path")]
    EmptyPath {
        /// What was to be written ("video").
        kind: String,
    },
    /// What is at the path cannot be looked at.
    #[error("cannot look at {} ({source})", path.display())]
    Inaccessible {
        /// Where the output was to go.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A folder is at the path.
    #[error("{} is a folder: give a file's path for the {kind}", path.display())]
    Folder {
        /// Where the output was to go.
        path: PathBuf,
        /// What was to be written ("video").
        kind: String,
    },
    /// A disk is at the path.
    #[error(
        "{} is a disk (a block device): yarok does not write a {kind} over a disk; give a \
         file's path",
        path.display()
    )]
    BlockDevice {
        /// Where the output was to go.
        path: PathBuf,
        /// What was to be written ("video").
        kind: String,
    },
    /// A socket is at the path.
    #[error("{} is a socket: give a file's path for the {kind}", path.display())]
    Socket {
        /// Where the output was to go.
        path: PathBuf,
        /// What was to be written ("video").
        kind: String,
    },
    /// A named pipe no process reads is at the path: writing would wait forever.
    #[error(
        "{} is a named pipe nobody reads ({source}): writing the {kind} would wait forever; \
         start its reader first, or give a file's path",
        path.display()
    )]
    PipeWithoutReader {
        /// Where the output was to go.
        path: PathBuf,
        /// What was to be written ("video").
        kind: String,
        /// Why.
        source: std::io::Error,
    },
    /// A file yarok did not write is at the path.
    #[error(
        "{} exists and is not a {kind} yarok wrote: yarok does not replace a file it did not \
         write; move it away or give another path",
        path.display()
    )]
    NotYaroks {
        /// Where the output was to go.
        path: PathBuf,
        /// What was to be written ("video").
        kind: String,
    },
    /// A file is at the path that cannot be read, so whether yarok wrote it is unknown.
    #[error(
        "{} exists and cannot be read ({source}), so yarok cannot tell it wrote it: it is left \
         as it is; move it away or give another path",
        path.display()
    )]
    Unreadable {
        /// Where the output was to go.
        path: PathBuf,
        /// What was to be written ("video").
        kind: String,
        /// Why.
        source: std::io::Error,
    },
    /// The folder the output goes in cannot be made.
    #[error("cannot make the folder {} ({source})", folder.display())]
    Folderless {
        /// The folder.
        folder: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Another live run writes the same output.
    #[error("another yarok run (process {pid}) is writing {what}")]
    Locked {
        /// The output, as a refusal names it.
        what: String,
        /// The process writing it.
        pid: u32,
    },
    /// Another run is writing its lock at this very moment.
    #[error(
        "another yarok run is starting to write {what} (its lock {} is being written)",
        lock.display()
    )]
    LockStarting {
        /// The output, as a refusal names it.
        what: String,
        /// The lock's file.
        lock: PathBuf,
    },
    /// Another run took the lock between two attempts.
    #[error("another yarok run took {} at the same time", lock.display())]
    LockRace {
        /// The lock's file.
        lock: PathBuf,
    },
    /// A file, folder or link of the user's is at the lock's name.
    #[error(
        "{} is in the way of the lock of {} and is not one yarok wrote (a lock is a file \
         holding a process id): move it away, or give another path",
        lock.display(),
        output.display()
    )]
    LockInTheWay {
        /// The lock's file.
        lock: PathBuf,
        /// The output the lock is for.
        output: PathBuf,
    },
    /// The lock cannot be created, written or (left by a run that ended) removed.
    #[error("cannot {action} {} ({source})", lock.display())]
    LockFailed {
        /// What could not be done.
        action: &'static str,
        /// The lock's file.
        lock: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The output cannot be written (its file beside the path created, written, flushed or
    /// renamed into place).
    #[error("cannot write {} ({source})", path.display())]
    Unwritable {
        /// Where the output was to go.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Something yarok did not write appeared at the path while the output was written: it is
    /// left as it is, and the output is kept beside it.
    #[error(
        "{} appeared while yarok wrote it and is not one yarok wrote: it is left as it is; \
         what yarok wrote is kept in {}",
        path.display(),
        kept.display()
    )]
    Appeared {
        /// Where the output was to go.
        path: PathBuf,
        /// Where what yarok wrote is.
        kept: PathBuf,
    },
}
