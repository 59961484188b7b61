//! Standard output that a closed pipe or a full disk does not crash: `yarok run … | head`,
//! `> /dev/full`. `println!` panics on both.

use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once a write found standard output closed (its reader went away) or failing: later
/// lines are dropped without trying again.
static GONE: AtomicBool = AtomicBool::new(false);

/// Writes `text` to standard output and flushes it. `Ok(false)` when standard output is closed
/// (a reader such as `head` went away): the caller should stop writing, as Unix tools do.
///
/// # Errors
///
/// Any other failure to write (a full disk, say).
///
/// # Examples
///
/// ```
/// let written = yarok_core::stdout::write("a composed world\n")?;
/// assert!(written);
/// # Ok::<(), std::io::Error>(())
/// ```
pub fn write(text: &str) -> std::io::Result<bool> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(true),
        Err(error) if error.kind() == ErrorKind::BrokenPipe => {
            GONE.store(true, Ordering::Relaxed);
            Ok(false)
        }
        Err(error) => Err(error),
    }
}

/// Prints `line` and a newline on standard output, for logs: if standard output is closed the
/// line is dropped, and if it fails otherwise it is dropped with one warning (the run goes on).
pub fn print_line(line: &str) {
    if GONE.load(Ordering::Relaxed) {
        return;
    }
    if let Err(error) = write(&format!("{line}\n")) {
        GONE.store(true, Ordering::Relaxed);
        tracing::warn!(%error, "standard output fails: log lines are no longer printed");
    }
}
