//! [`Dashboard`]: the UR controller's dashboard server (port 29999), one ASCII line a command
//! and one a reply.

use std::time::Duration;

use tokio::io::{AsyncRead, AsyncWrite, AsyncWriteExt, BufReader};

use crate::reading::{Unread, line_by};

/// The longest reply line kept.
const MAX_LINE: usize = 4096;

/// What went wrong on the dashboard. Every variant names the controller.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DashboardError {
    /// Reading or writing failed.
    #[error("controller {controller}: dashboard: {source}")]
    Io {
        /// The controller.
        controller: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The connection closed (the controller allows one dashboard client at a time on some
    /// versions).
    #[error("controller {controller}: the dashboard closed while `{command}` waited")]
    Closed {
        /// The controller.
        controller: String,
        /// The command, or `welcome`.
        command: String,
    },
    /// No reply in time.
    #[error("controller {controller}: no dashboard reply to `{command}` within {seconds} s")]
    Timeout {
        /// The controller.
        controller: String,
        /// The command.
        command: String,
        /// The time limit.
        seconds: f64,
    },
    /// The controller did not do what was asked; its reply says why.
    #[error("controller {controller}: `{command}` failed: {reply}")]
    Failed {
        /// The controller.
        controller: String,
        /// The command.
        command: String,
        /// What the controller answered.
        reply: String,
    },
    /// The command cannot be sent: it holds a line break.
    #[error("`{command:?}` is not a dashboard command")]
    Invalid {
        /// The command.
        command: String,
    },
}

/// The arm's mode, as the dashboard reports it (`robotmode`).
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum RobotMode {
    /// `POWER_OFF`.
    PowerOff,
    /// `POWER_ON`.
    PowerOn,
    /// `IDLE`: powered, brakes engaged.
    Idle,
    /// `RUNNING`: ready to move.
    Running,
    /// Any other mode (`BOOTING`, `BACKDRIVE`, …), as the controller named it.
    Other(String),
}

/// The safety system's state (`safetystatus` on e-Series, `safetymode` on CB3).
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum SafetyStatus {
    /// `NORMAL`.
    Normal,
    /// `REDUCED`.
    Reduced,
    /// `PROTECTIVE_STOP`: unlock with [`Dashboard::unlock_protective_stop`].
    ProtectiveStop,
    /// Any other state (`SAFEGUARD_STOP`, `ROBOT_EMERGENCY_STOP`, `FAULT`, …), as named.
    Other(String),
}

/// A client of the dashboard server over any byte transport (a TCP stream to port 29999):
/// power, brakes, protective stops, safety pop-ups, programs, and the arm's modes. Every
/// reply is awaited within the time limit it was made with.
///
/// ```no_run
/// # async fn run() -> Result<(), Box<dyn std::error::Error>> {
/// use std::time::Duration;
/// use tokio::net::TcpStream;
/// use yarok_hw::ur::dashboard::{Dashboard, RobotMode};
///
/// let stream = TcpStream::connect("192.168.1.10:29999").await?;
/// let mut dashboard = Dashboard::connect(stream, "192.168.1.10", Duration::from_secs(2)).await?;
/// if dashboard.robot_mode().await? != RobotMode::Running {
///     dashboard.power_on().await?;
///     dashboard.brake_release().await?;
/// }
/// # Ok(()) }
/// ```
///
/// # Cancel safety
///
/// Not cancel safe: a reply left unread would answer the next command. Reconnect after
/// dropping a command's future.
#[derive(Debug)]
pub struct Dashboard<T> {
    stream: BufReader<T>,
    controller: String,
    timeout: Duration,
    version: Option<u32>,
    partial: Vec<u8>,
}

impl<T: AsyncRead + AsyncWrite + Unpin> Dashboard<T> {
    /// Reads the server's welcome over `transport` (the controller called `controller` in
    /// errors); each reply may take up to `timeout`.
    ///
    /// # Errors
    ///
    /// [`DashboardError`] when no welcome comes.
    pub async fn connect(
        transport: T,
        controller: impl Into<String>,
        timeout: Duration,
    ) -> Result<Self, DashboardError> {
        let mut dashboard = Self {
            stream: BufReader::new(transport),
            controller: controller.into(),
            timeout,
            version: None,
            partial: Vec::new(),
        };
        let welcome = dashboard.reply("welcome").await?;
        if !welcome.starts_with("Connected: Universal Robots Dashboard Server") {
            return Err(dashboard.failed("welcome", welcome));
        }
        Ok(dashboard)
    }

    /// Sends `command` and returns the controller's reply line.
    ///
    /// # Errors
    ///
    /// [`DashboardError`].
    pub async fn command(&mut self, command: &str) -> Result<String, DashboardError> {
        if command.contains(['\n', '\r']) {
            return Err(DashboardError::Invalid {
                command: command.to_owned(),
            });
        }
        let line = format!("{command}\n");
        let written = async {
            self.stream.get_mut().write_all(line.as_bytes()).await?;
            self.stream.get_mut().flush().await
        };
        written.await.map_err(|source| DashboardError::Io {
            controller: self.controller.clone(),
            source,
        })?;
        self.reply(command).await
    }

    /// Powers the arm on (`power on`).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] with the controller's reason.
    pub async fn power_on(&mut self) -> Result<(), DashboardError> {
        self.expect("power on", "Powering on").await
    }

    /// Releases the brakes (`brake release`).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] with the controller's reason.
    pub async fn brake_release(&mut self) -> Result<(), DashboardError> {
        self.expect("brake release", "Brake releasing").await
    }

    /// Unlocks a protective stop (`unlock protective stop`; the controller refuses within 5 s
    /// of the stop).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] with the controller's reason.
    pub async fn unlock_protective_stop(&mut self) -> Result<(), DashboardError> {
        self.expect("unlock protective stop", "Protective stop releasing")
            .await
    }

    /// Closes a safety pop-up (`close safety popup`).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] with the controller's reason.
    pub async fn close_safety_popup(&mut self) -> Result<(), DashboardError> {
        self.expect("close safety popup", "closing safety popup")
            .await
    }

    /// Loads the program `path` (`load`).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] (`File not found: …`).
    pub async fn load(&mut self, path: &str) -> Result<(), DashboardError> {
        self.expect(&format!("load {path}"), "Loading program:")
            .await
    }

    /// Starts the loaded program (`play`).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] (`Failed to execute: play`).
    pub async fn play(&mut self) -> Result<(), DashboardError> {
        self.expect("play", "Starting program").await
    }

    /// Stops the running program (`stop`).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] (`Failed to execute: stop`).
    pub async fn stop(&mut self) -> Result<(), DashboardError> {
        self.expect("stop", "Stopped").await
    }

    /// The software version (`PolyscopeVersion`), e.g. `URSoftware 5.11.1.108318 (Mar 22 2022)`.
    ///
    /// # Errors
    ///
    /// [`DashboardError`].
    pub async fn polyscope_version(&mut self) -> Result<String, DashboardError> {
        let reply = self.command("PolyscopeVersion").await?;
        self.version = reply
            .split_whitespace()
            .nth(1)
            .and_then(|version| version.split('.').next()?.parse().ok());
        Ok(reply)
    }

    /// The arm's mode (`robotmode`).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] for a reply that is no mode.
    pub async fn robot_mode(&mut self) -> Result<RobotMode, DashboardError> {
        let mode = self.labelled("robotmode", "Robotmode: ").await?;
        Ok(match mode.as_str() {
            "POWER_OFF" => RobotMode::PowerOff,
            "POWER_ON" => RobotMode::PowerOn,
            "IDLE" => RobotMode::Idle,
            "RUNNING" => RobotMode::Running,
            _ => RobotMode::Other(mode),
        })
    }

    /// The safety system's state: `safetystatus` on e-Series (5.x), `safetymode` on CB3 (the
    /// version is asked once when not known).
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] for a reply that is no state.
    pub async fn safety_status(&mut self) -> Result<SafetyStatus, DashboardError> {
        if self.version.is_none() {
            self.polyscope_version().await?;
        }
        let status = if self.version.is_some_and(|major| major >= 5) {
            self.labelled("safetystatus", "Safetystatus: ").await?
        } else {
            self.labelled("safetymode", "Safetymode: ").await?
        };
        Ok(match status.as_str() {
            "NORMAL" => SafetyStatus::Normal,
            "REDUCED" => SafetyStatus::Reduced,
            "PROTECTIVE_STOP" => SafetyStatus::ProtectiveStop,
            _ => SafetyStatus::Other(status),
        })
    }

    /// Whether the controller takes commands from the network (`is in remote control`): an
    /// e-Series controller in local control runs no script sent to it and refuses `play`. A CB3
    /// controller (3.x) has no local mode and is not asked.
    ///
    /// # Errors
    ///
    /// [`DashboardError::Failed`] for a reply that is neither `true` nor `false`.
    pub async fn is_in_remote_control(&mut self) -> Result<bool, DashboardError> {
        if self.version.is_none() {
            self.polyscope_version().await?;
        }
        if self.version.is_some_and(|major| major < 5) {
            return Ok(true);
        }
        let command = "is in remote control";
        let reply = self.command(command).await?;
        match reply.trim() {
            "true" => Ok(true),
            "false" => Ok(false),
            _ => Err(self.failed(command, reply)),
        }
    }

    /// Sends `command`; its reply must start with `success`.
    async fn expect(&mut self, command: &str, success: &str) -> Result<(), DashboardError> {
        let reply = self.command(command).await?;
        if reply.starts_with(success) {
            Ok(())
        } else {
            Err(self.failed(command, reply))
        }
    }

    /// Sends `command`; its reply is `label` and a value, returned.
    async fn labelled(&mut self, command: &str, label: &str) -> Result<String, DashboardError> {
        let reply = self.command(command).await?;
        match reply.strip_prefix(label) {
            Some(value) => Ok(value.trim().to_owned()),
            None => Err(self.failed(command, reply)),
        }
    }

    fn failed(&self, command: &str, reply: String) -> DashboardError {
        DashboardError::Failed {
            controller: self.controller.clone(),
            command: command.to_owned(),
            reply,
        }
    }

    /// The next reply line, without its ending, within the time limit.
    async fn reply(&mut self, command: &str) -> Result<String, DashboardError> {
        let deadline = tokio::time::Instant::now() + self.timeout;
        let read = line_by(&mut self.stream, &mut self.partial, MAX_LINE, deadline);
        read.await.map_err(|unread| match unread {
            Unread::Closed => DashboardError::Closed {
                controller: self.controller.clone(),
                command: command.to_owned(),
            },
            Unread::Failed(source) => DashboardError::Io {
                controller: self.controller.clone(),
                source,
            },
            Unread::TimedOut => DashboardError::Timeout {
                controller: self.controller.clone(),
                command: command.to_owned(),
                seconds: self.timeout.as_secs_f64(),
            },
        })
    }
}
