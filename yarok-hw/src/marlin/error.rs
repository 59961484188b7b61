//! [`MarlinError`]: what can go wrong talking to a Marlin printer, naming the printer and the
//! command.

/// What went wrong talking to a printer. Every variant but [`MarlinError::InvalidCommand`] names
/// the printer (its port, or the name its settings give).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MarlinError {
    /// Reading or writing failed (the port went away).
    #[error("printer {printer}: {source}")]
    Io {
        /// The printer.
        printer: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The connection closed (the printer was unplugged or reset).
    #[error("printer {printer}: the connection closed while waiting for `{command}`")]
    Closed {
        /// The printer.
        printer: String,
        /// The command waiting for its answer (or the start-up's).
        command: String,
    },
    /// The printer sent nothing, not even a keep-alive, for too long.
    #[error("printer {printer}: no answer to `{command}` for {seconds} s (is it on?)")]
    Silent {
        /// The printer.
        printer: String,
        /// The command.
        command: String,
        /// How long it was silent.
        seconds: f64,
    },
    /// The command did not finish in time, though the printer kept talking.
    #[error("printer {printer}: `{command}` did not finish within {seconds} s")]
    Timeout {
        /// The printer.
        printer: String,
        /// The command.
        command: String,
        /// Its time limit.
        seconds: f64,
    },
    /// The printer reported an error for the command (`Error:…`, `!! …`).
    #[error("printer {printer}: `{command}` failed: {message}")]
    Printer {
        /// The printer.
        printer: String,
        /// The command.
        command: String,
        /// What the printer said.
        message: String,
    },
    /// The printer halted itself (`kill()`); it must be reset before it answers again.
    #[error("printer {printer} halted: {message}")]
    Halted {
        /// The printer.
        printer: String,
        /// What it said.
        message: String,
    },
    /// The printer rebooted while a command waited for its answer: the command is lost.
    #[error("printer {printer} restarted while `{command}` waited for its answer")]
    Restarted {
        /// The printer.
        printer: String,
        /// The lost command.
        command: String,
    },
    /// The printer asked for the command again and again (a noisy line).
    #[error("printer {printer}: `{command}` was asked for again {resends} times")]
    ResendStorm {
        /// The printer.
        printer: String,
        /// The command.
        command: String,
        /// How many times.
        resends: u32,
    },
    /// The printer did not acknowledge the start-up `M110 N0` within its boot time.
    #[error(
        "printer {printer}: no answer to `M110 N0` within {seconds} s of opening it (is it on, and \
         at this baud rate? {})",
        match last_heard {
            Some(line) => format!("last heard: {:?}", line.chars().take(60).collect::<String>()),
            None => "it sent nothing".to_owned(),
        }
    )]
    NoHandshake {
        /// The printer.
        printer: String,
        /// The boot time allowed.
        seconds: f64,
        /// The last line it sent, if any (garbage suggests a wrong baud rate).
        last_heard: Option<String>,
    },
    /// The printer went idle (`wait`, twice) while a command waited for its answer: the `ok`
    /// was lost on the line.
    #[error("printer {printer} is idle but never answered `{command}`: its `ok` was lost")]
    LostAnswer {
        /// The printer.
        printer: String,
        /// The command.
        command: String,
    },
    /// The printer answered without the position asked for.
    #[error("printer {printer}: `{command}` answered without a position")]
    NoPosition {
        /// The printer.
        printer: String,
        /// The command.
        command: String,
    },
    /// The printer's transport could not be opened.
    #[error("printer {printer}: cannot open it: {source}")]
    Open {
        /// The printer.
        printer: String,
        /// Why.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The connection dropped and the printer came back: the board restarted, so the work
    /// that was running is lost and the head's position unknown until it is homed again.
    #[error(
        "printer {printer} was reconnected after its connection dropped ({cause}); it restarted, \
         so home it before moving again"
    )]
    Reconnected {
        /// The printer.
        printer: String,
        /// How the connection dropped.
        cause: Box<MarlinError>,
    },
    /// The connection dropped and the printer did not come back in time.
    #[error("printer {printer} is gone: not back within {seconds} s ({source})")]
    Unplugged {
        /// The printer.
        printer: String,
        /// How long it was waited for.
        seconds: f64,
        /// Why the last attempt to reconnect failed.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The command cannot be sent: empty, or holding `*`, `;`, a line break or a non-ASCII
    /// character.
    #[error("`{command}` is not a command that can be sent")]
    InvalidCommand {
        /// The command.
        command: String,
    },
}

impl MarlinError {
    /// Whether the connection itself was lost (the port closed or failed), as when a USB
    /// printer is unplugged — rather than the printer answering with a failure.
    pub fn is_connection_lost(&self) -> bool {
        matches!(self, Self::Closed { .. } | Self::Io { .. })
    }
}
