//! [`XServer`]: an Xvfb of a test's own, on a display Xvfb chose free.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

/// An Xvfb server (1280×1024, 24-bit, no TCP) on a display of its own, stopped when dropped.
///
/// Xvfb picks the display itself (`-displayfd`), taking its lock file atomically, so tests in
/// parallel processes never share a server, and the sockets a killed server leaves behind do
/// not matter.
#[derive(Debug)]
pub struct XServer {
    display: String,
    server: Child,
}

impl XServer {
    /// Starts Xvfb and waits until it accepts clients.
    ///
    /// # Panics
    ///
    /// When Xvfb is not installed (`scripts/setup-test-peers.sh` installs it) or does not
    /// start.
    pub fn start() -> Self {
        let mut server = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", "1280x1024x24"])
            .args(["-nolisten", "tcp"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb runs (scripts/setup-test-peers.sh installs it)");
        // Xvfb writes the display's number once it listens, and closes the pipe if it fails.
        let mut number = String::new();
        let stdout = server.stdout.take().expect("Xvfb's standard output");
        BufReader::new(stdout)
            .read_line(&mut number)
            .expect("Xvfb's display number");
        let number = number.trim();
        assert!(
            !number.is_empty() && number.bytes().all(|b| b.is_ascii_digit()),
            "Xvfb did not start (it wrote {number:?} for its display)"
        );
        Self {
            display: format!(":{number}"),
            server,
        }
    }

    /// The display, as `DISPLAY` takes it (`:12`).
    pub fn display(&self) -> &str {
        &self.display
    }
}

impl Drop for XServer {
    fn drop(&mut self) {
        // Asked to end, Xvfb removes its socket and lock file.
        let stopped = Command::new("kill")
            .args(["-TERM", &self.server.id().to_string()])
            .status()
            .is_ok_and(|status| status.success());
        if !stopped {
            let _ = self.server.kill();
        }
        let _ = self.server.wait();
    }
}
