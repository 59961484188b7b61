//! [`Gripper`]: a Robotiq 2F gripper through its URCap socket server (port 63352 on the UR
//! controller): ASCII lines, `GET <VAR>` answered `<VAR> <value>`, `SET <VAR> <value> …`
//! answered `ack`.

use std::time::Duration;

use tokio::io::{AsyncRead, AsyncWrite, AsyncWriteExt, BufReader};
use tokio::time::Instant;

use crate::reading::{Unread, line_by};

/// The longest reply line kept.
const MAX_LINE: usize = 256;

/// What went wrong with the gripper. Every variant names it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GripperError {
    /// Reading or writing failed.
    #[error("gripper {gripper}: {source}")]
    Io {
        /// The gripper (its controller's address).
        gripper: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The connection closed.
    #[error("gripper {gripper}: the connection closed while `{command}` waited")]
    Closed {
        /// The gripper.
        gripper: String,
        /// The command.
        command: String,
    },
    /// No reply, or the motion or activation did not finish, in time.
    #[error("gripper {gripper}: `{command}` did not finish within {seconds} s")]
    Timeout {
        /// The gripper.
        gripper: String,
        /// The command or operation.
        command: String,
        /// The time limit.
        seconds: f64,
    },
    /// A reply that is not what the command is answered with.
    #[error("gripper {gripper}: `{command}` was answered `{reply}`")]
    Unexpected {
        /// The gripper.
        gripper: String,
        /// The command.
        command: String,
        /// The reply.
        reply: String,
    },
    /// The gripper reports a fault (`FLT`).
    #[error("gripper {gripper}: fault {code}: {meaning}")]
    Fault {
        /// The gripper.
        gripper: String,
        /// The fault code.
        code: u8,
        /// What it means.
        meaning: &'static str,
    },
}

/// What a fault code means (Robotiq 2F manual).
fn fault_meaning(code: u8) -> &'static str {
    match code {
        5 => "action delayed: activation must complete first",
        7 => "the gripper must be activated first",
        8 => "maximum operating temperature exceeded",
        10 => "under minimum operating voltage",
        11 => "automatic release in progress",
        12 => "internal fault",
        13 => "activation fault: check that nothing blocks the fingers",
        14 => "overcurrent triggered",
        15 => "automatic release completed",
        _ => "see the gripper's manual",
    }
}

/// Where the fingers stopped (`OBJ`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Motion {
    /// `0`: moving.
    Moving,
    /// `1`: stopped on an object while opening.
    ObjectWhileOpening,
    /// `2`: stopped on an object while closing — a grasp.
    ObjectWhileClosing,
    /// `3`: at the requested position, no object.
    AtPosition,
}

/// The gripper's state, read with `GET`s.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GripperState {
    /// Finger position, 0 (open) … 255 (closed).
    pub position: u8,
    /// The position last asked for (`PRE`).
    pub requested: u8,
    /// Where the motion stands (`OBJ`).
    pub motion: Motion,
}

/// A Robotiq 2F gripper (2F-85, 2F-140) through the URCap socket server, over any byte
/// transport (a TCP stream to the controller's port 63352): activation, moves with speed and
/// force, grasp detection, faults as errors. Every reply is awaited within the time limit it
/// was made with; motions and activation within theirs.
///
/// ```no_run
/// # async fn run() -> Result<(), Box<dyn std::error::Error>> {
/// use std::time::Duration;
/// use tokio::net::TcpStream;
/// use yarok_hw::robotiq::{Gripper, Motion};
///
/// let stream = TcpStream::connect("192.168.1.10:63352").await?;
/// let mut gripper = Gripper::new(stream, "192.168.1.10", Duration::from_secs(1));
/// gripper.activate(Duration::from_secs(5)).await?;
/// gripper.go_to(255, 128, 100).await?;
/// let state = gripper.finish_motion(Duration::from_secs(3)).await?;
/// let grasped = state.motion == Motion::ObjectWhileClosing;
/// # Ok(()) }
/// ```
///
/// # Cancel safety
///
/// Not cancel safe: a reply left unread would answer the next command. Reconnect after
/// dropping a command's future.
#[derive(Debug)]
pub struct Gripper<T> {
    stream: BufReader<T>,
    partial: Vec<u8>,
    gripper: String,
    timeout: Duration,
    poll: Duration,
}

impl<T: AsyncRead + AsyncWrite + Unpin> Gripper<T> {
    /// A gripper over `transport`, called `gripper` in errors, whose every reply may take up
    /// to `timeout`. Its state is polled every 10 ms while waiting.
    pub fn new(transport: T, gripper: impl Into<String>, timeout: Duration) -> Self {
        Self {
            stream: BufReader::new(transport),
            partial: Vec::new(),
            gripper: gripper.into(),
            timeout,
            poll: Duration::from_millis(10),
        }
    }

    /// The variable `name` (`POS`, `OBJ`, `STA`, `FLT`, …).
    ///
    /// # Errors
    ///
    /// [`GripperError`].
    pub async fn get(&mut self, name: &str) -> Result<u8, GripperError> {
        let command = format!("GET {name}");
        let reply = self.exchange(&command).await?;
        let value = reply
            .strip_prefix(name)
            .and_then(|rest| rest.strip_prefix(' '))
            .and_then(|value| value.trim().parse().ok());
        value.ok_or_else(|| self.unexpected(&command, reply))
    }

    /// Sets the variables `pairs` in one command (`SET POS 100 SPE 255 …`).
    ///
    /// # Errors
    ///
    /// [`GripperError`]; [`GripperError::Unexpected`] when it is not acknowledged.
    pub async fn set(&mut self, pairs: &[(&str, u8)]) -> Result<(), GripperError> {
        let mut command = String::from("SET");
        for (name, value) in pairs {
            command.push_str(&format!(" {name} {value}"));
        }
        let reply = self.exchange(&command).await?;
        if reply == "ack" {
            Ok(())
        } else {
            Err(self.unexpected(&command, reply))
        }
    }

    /// Activates the gripper (as Robotiq's URCap does: reset, then `ACT 1`) and waits until it
    /// is active, within `limit`.
    ///
    /// # Errors
    ///
    /// [`GripperError::Fault`] (an activation fault), [`GripperError::Timeout`].
    pub async fn activate(&mut self, limit: Duration) -> Result<(), GripperError> {
        let until = Instant::now() + limit;
        self.set(&[("ACT", 0), ("ATR", 0)]).await?;
        while !(self.get("ACT").await? == 0 && self.get("STA").await? == 0) {
            self.pause(until, limit, "reset").await?;
            self.set(&[("ACT", 0), ("ATR", 0)]).await?;
        }
        self.set(&[("ACT", 1)]).await?;
        while !(self.get("ACT").await? == 1 && self.get("STA").await? == 3) {
            self.check_fault().await?;
            self.pause(until, limit, "activation").await?;
        }
        Ok(())
    }

    /// Starts a move of the fingers to `position` (0 open … 255 closed) at `speed` and with
    /// `force` (0 … 255 each); returns once the gripper took it.
    ///
    /// # Errors
    ///
    /// [`GripperError`].
    pub async fn go_to(&mut self, position: u8, speed: u8, force: u8) -> Result<(), GripperError> {
        self.set(&[
            ("POS", position),
            ("SPE", speed),
            ("FOR", force),
            ("GTO", 1),
        ])
        .await
    }

    /// Waits until the motion asked for last has ended — at the position, or stopped on an
    /// object — within `limit`.
    ///
    /// # Errors
    ///
    /// [`GripperError::Fault`] when the gripper faults, [`GripperError::Timeout`].
    pub async fn finish_motion(&mut self, limit: Duration) -> Result<GripperState, GripperError> {
        let until = Instant::now() + limit;
        loop {
            self.check_fault().await?;
            let state = self.state().await?;
            if state.motion != Motion::Moving {
                return Ok(state);
            }
            self.pause(until, limit, "the motion").await?;
        }
    }

    /// Position, requested position and motion.
    ///
    /// # Errors
    ///
    /// [`GripperError`].
    pub async fn state(&mut self) -> Result<GripperState, GripperError> {
        let motion = match self.get("OBJ").await? {
            0 => Motion::Moving,
            1 => Motion::ObjectWhileOpening,
            2 => Motion::ObjectWhileClosing,
            _ => Motion::AtPosition,
        };
        Ok(GripperState {
            position: self.get("POS").await?,
            requested: self.get("PRE").await?,
            motion,
        })
    }

    /// [`GripperError::Fault`] when `FLT` is not 0.
    ///
    /// # Errors
    ///
    /// The fault; other [`GripperError`]s.
    pub async fn check_fault(&mut self) -> Result<(), GripperError> {
        match self.get("FLT").await? {
            0 => Ok(()),
            code => Err(GripperError::Fault {
                gripper: self.gripper.clone(),
                code,
                meaning: fault_meaning(code),
            }),
        }
    }

    /// Sleeps one poll interval, unless that passes `until`, the end of `limit`.
    async fn pause(&self, until: Instant, limit: Duration, what: &str) -> Result<(), GripperError> {
        let next = Instant::now() + self.poll;
        if next > until {
            return Err(GripperError::Timeout {
                gripper: self.gripper.clone(),
                command: what.to_owned(),
                seconds: limit.as_secs_f64(),
            });
        }
        tokio::time::sleep_until(next).await;
        Ok(())
    }

    fn unexpected(&self, command: &str, reply: String) -> GripperError {
        GripperError::Unexpected {
            gripper: self.gripper.clone(),
            command: command.to_owned(),
            reply,
        }
    }

    /// Sends `command` and reads its reply line, both within the time limit.
    async fn exchange(&mut self, command: &str) -> Result<String, GripperError> {
        let deadline = Instant::now() + self.timeout;
        let line = format!("{command}\n");
        let written = async {
            self.stream.get_mut().write_all(line.as_bytes()).await?;
            self.stream.get_mut().flush().await
        };
        let unread = match tokio::time::timeout_at(deadline, written).await {
            Ok(Ok(())) => line_by(&mut self.stream, &mut self.partial, MAX_LINE, deadline).await,
            Ok(Err(source)) => Err(Unread::Failed(source)),
            Err(_) => Err(Unread::TimedOut),
        };
        unread
            .map(|reply| reply.trim().to_owned())
            .map_err(|unread| match unread {
                Unread::Closed => GripperError::Closed {
                    gripper: self.gripper.clone(),
                    command: command.to_owned(),
                },
                Unread::Failed(source) => GripperError::Io {
                    gripper: self.gripper.clone(),
                    source,
                },
                Unread::TimedOut => GripperError::Timeout {
                    gripper: self.gripper.clone(),
                    command: command.to_owned(),
                    seconds: self.timeout.as_secs_f64(),
                },
            })
    }
}
