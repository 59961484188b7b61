//! [`Secondary`]: a client of the secondary interface (port 30002): the robot state at 10 Hz,
//! and URScript sent to run.

use std::time::Duration;

use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt};

use super::packet::{Packet, PacketError, RobotState, VersionMessage, parse, take_packet};
use crate::reading::{Unread, read_more};

/// What went wrong on the secondary interface. Every variant names the controller.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SecondaryError {
    /// Reading or writing failed.
    #[error("controller {controller}: secondary interface: {source}")]
    Io {
        /// The controller.
        controller: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The connection closed.
    #[error("controller {controller}: the secondary interface closed")]
    Closed {
        /// The controller.
        controller: String,
    },
    /// No robot state in time.
    #[error("controller {controller}: no robot state within {seconds} s")]
    Silent {
        /// The controller.
        controller: String,
        /// The time limit.
        seconds: f64,
    },
    /// A packet was malformed.
    #[error("controller {controller}: {source}")]
    Packet {
        /// The controller.
        controller: String,
        /// What is wrong.
        source: PacketError,
    },
}

/// Sends URScript over a secondary-interface connection without reading from it: what to send at
/// shutdown, when the controller may have stopped sending robot states (a [`Secondary`] waits
/// for one to connect).
///
/// ```
/// # async fn run() -> std::io::Result<()> {
/// let (mut ours, theirs) = tokio::io::duplex(64);
/// yarok_hw::ur::secondary::send_script(&mut ours, "stopj(2.0)").await?;
/// # Ok(()) }
/// ```
///
/// # Errors
///
/// When the transport cannot be written.
pub async fn send_script<T: AsyncWrite + Unpin>(
    transport: &mut T,
    script: &str,
) -> std::io::Result<()> {
    let text = format!("{}\n", script.trim_end());
    transport.write_all(text.as_bytes()).await?;
    transport.flush().await
}

/// Sends URScript over a connection of its own, then closes it cleanly: the sending side shut
/// and what the controller sends (its version message, robot states) drained until it closes
/// too, for at most `linger`. The controller writes before and while it reads; a client gone
/// at once makes its next write fail, and a controller that then drops the connection may do
/// so before it has read the line: the `stopj` a program sends as it exits would be lost.
///
/// ```
/// # async fn run() -> std::io::Result<()> {
/// use std::time::Duration;
/// use tokio::io::AsyncReadExt;
///
/// let (mut ours, mut theirs) = tokio::io::duplex(64);
/// let controller = async move {
///     let mut received = String::new();
///     theirs.read_to_string(&mut received).await?;
///     drop(theirs);
///     Ok::<_, std::io::Error>(received)
/// };
/// let sending = yarok_hw::ur::secondary::send_script_and_close(
///     &mut ours,
///     "stopj(2.0)",
///     Duration::from_millis(250),
/// );
/// let (sent, received) = tokio::join!(sending, controller);
/// sent?;
/// assert_eq!(received?, "stopj(2.0)\n");
/// # Ok(()) }
/// ```
///
/// # Errors
///
/// When the transport cannot be written or shut. What it reads, and how, does not matter.
pub async fn send_script_and_close<T: AsyncRead + AsyncWrite + Unpin>(
    transport: &mut T,
    script: &str,
    linger: Duration,
) -> std::io::Result<()> {
    send_script(transport, script).await?;
    transport.shutdown().await?;
    let mut unread = [0; 4096];
    let drained = async { while let Ok(1..) = transport.read(&mut unread).await {} };
    let _closed_or_lingered = tokio::time::timeout(linger, drained).await;
    Ok(())
}

/// A client of the UR controller's secondary interface over any byte transport (a TCP stream
/// to port 30002): it reads the robot states the controller sends at 10 Hz (mode, joints, TCP,
/// kinematics; CB3 and e-Series layouts, unknown sub-packages skipped) and the version message,
/// and sends URScript, which the controller runs at once (replacing a running program).
///
/// ```no_run
/// # async fn run() -> Result<(), Box<dyn std::error::Error>> {
/// use std::time::Duration;
/// use tokio::net::TcpStream;
/// use yarok_hw::ur::secondary::Secondary;
///
/// let stream = TcpStream::connect("192.168.1.10:30002").await?;
/// let mut secondary = Secondary::connect(stream, "192.168.1.10", Duration::from_secs(1)).await?;
/// secondary.send_script("movej([0, -1.57, 1.57, -1.57, -1.57, 0], a=1.4, v=1.05)").await?;
/// let state = secondary.next_state().await?;
/// let running = state.mode.is_some_and(|mode| mode.program_running);
/// # Ok(()) }
/// ```
///
/// # Cancel safety
///
/// [`Secondary::next_state`] is cancel safe: bytes read stay for the next call, and its silence
/// limit counts from the last robot state, not from the call, so a loop that drops and makes the
/// call again (a `select!` beside a faster stream) still finds a controller gone silent.
#[derive(Debug)]
pub struct Secondary<T> {
    stream: T,
    buffer: Vec<u8>,
    controller: String,
    silence: Duration,
    version: Option<VersionMessage>,
    latest: RobotState,
    /// When the last robot state came (the connection's start, before the first).
    heard: tokio::time::Instant,
}

impl<T: AsyncRead + AsyncWrite + Unpin> Secondary<T> {
    /// Reads from `transport` (the controller called `controller` in errors) until the first
    /// robot state ([`Secondary::latest`]); a state may take up to `silence` to come.
    ///
    /// # Errors
    ///
    /// [`SecondaryError`].
    pub async fn connect(
        transport: T,
        controller: impl Into<String>,
        silence: Duration,
    ) -> Result<Self, SecondaryError> {
        let mut secondary = Self {
            stream: transport,
            buffer: Vec::new(),
            controller: controller.into(),
            silence,
            version: None,
            latest: RobotState::default(),
            heard: tokio::time::Instant::now(),
        };
        secondary.next_state().await?;
        Ok(secondary)
    }

    /// The controller's version message, once it came (it comes first on connect).
    pub fn version(&self) -> Option<&VersionMessage> {
        self.version.as_ref()
    }

    /// The newest robot state read (the first one, right after connecting).
    pub fn latest(&self) -> &RobotState {
        &self.latest
    }

    /// The next robot state, within the silence limit.
    ///
    /// # Errors
    ///
    /// [`SecondaryError::Silent`] when none comes in time; other [`SecondaryError`]s.
    pub async fn next_state(&mut self) -> Result<RobotState, SecondaryError> {
        let deadline = self.heard + self.silence;
        loop {
            let taken = take_packet(&mut self.buffer).map_err(|source| self.packet(source))?;
            if let Some(packet) = taken {
                match parse(&packet).map_err(|source| self.packet(source))? {
                    Packet::RobotState(state) => {
                        self.latest = *state;
                        self.heard = tokio::time::Instant::now();
                        return Ok(self.latest);
                    }
                    Packet::Version(version) => self.version = Some(version),
                    _ => {}
                }
                continue;
            }
            let read = read_more(&mut self.stream, &mut self.buffer, deadline).await;
            read.map_err(|unread| match unread {
                Unread::Closed => SecondaryError::Closed {
                    controller: self.controller.clone(),
                },
                Unread::Failed(source) => SecondaryError::Io {
                    controller: self.controller.clone(),
                    source,
                },
                Unread::TimedOut => SecondaryError::Silent {
                    controller: self.controller.clone(),
                    seconds: self.silence.as_secs_f64(),
                },
            })?;
        }
    }

    /// Sends `script` (a URScript line, or a whole `def …: … end` program) to run now.
    ///
    /// # Errors
    ///
    /// [`SecondaryError::Io`].
    pub async fn send_script(&mut self, script: &str) -> Result<(), SecondaryError> {
        send_script(&mut self.stream, script)
            .await
            .map_err(|source| SecondaryError::Io {
                controller: self.controller.clone(),
                source,
            })
    }

    fn packet(&self, source: PacketError) -> SecondaryError {
        SecondaryError::Packet {
            controller: self.controller.clone(),
            source,
        }
    }
}
