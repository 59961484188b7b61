//! [`Marlin`]: an async G-code driver for Marlin printers, generic over its transport.

use std::time::Duration;

use tokio::io::{AsyncRead, AsyncWrite, AsyncWriteExt, BufReader};
use tokio::time::Instant;

use super::MarlinError;
use super::line::numbered_line;
use super::reply::{Position, Reply};
use crate::reading::{Unread, line_by, read_line};

/// The longest line kept from the printer; the rest of a longer one is dropped.
const MAX_LINE: usize = 512;

/// The start-up command that resets the line numbers.
const HANDSHAKE: &str = "M110 N0";

/// How long [`Marlin::connect`] waits for `M110`'s `ok` before sending it again.
pub const HANDSHAKE_RETRY: Duration = Duration::from_secs(1);

/// How long after a command is sent a `wait` line counts as the printer idle with it (earlier
/// ones were sent before the command arrived, or sat unread in the line's buffer).
const IDLE_GRACE: Duration = Duration::from_secs(1);

/// How a start-up `M110` fared.
enum Handshake {
    Acknowledged,
    /// The board (re)started: it did not see the command.
    Started,
    Unanswered,
}

/// How the driver talks to a printer; every wait is bounded by one of these.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct MarlinSettings {
    /// The printer's name in errors (its port).
    pub name: String,
    /// The longest the printer may send nothing at all, not even a keep-alive (Marlin sends
    /// `busy` every 2 s during long commands).
    pub silence: Duration,
    /// How long the board may take to boot after the port opens (many reset on open).
    pub boot_timeout: Duration,
    /// How long the line must stay quiet for the boot to count as over.
    pub boot_quiet: Duration,
    /// The longest an ordinary command may take to be acknowledged.
    pub command_timeout: Duration,
    /// The longest homing (`G28`) or finishing the moves (`M400`) may take.
    pub motion_timeout: Duration,
    /// How many times in a row a command may be asked for again before the line counts as
    /// broken.
    pub max_resends: u32,
    /// How long a printer whose connection dropped may take to come back, booted, before
    /// [`Reconnecting`](super::Reconnecting) gives up.
    pub replug_timeout: Duration,
}

impl MarlinSettings {
    /// Defaults for the printer called `name`: 5 s of silence, 10 s to boot (quiet for 1.5 s),
    /// 10 s a command, 5 min for homing and moves, 8 resends, 30 s to come back after an
    /// unplug.
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            silence: Duration::from_secs(5),
            boot_timeout: Duration::from_secs(10),
            boot_quiet: Duration::from_millis(1500),
            command_timeout: Duration::from_secs(10),
            motion_timeout: Duration::from_secs(300),
            max_resends: 8,
            replug_timeout: Duration::from_secs(30),
        }
    }
}

/// What the printer answered to a command besides its `ok`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct Answer {
    /// A position it reported (`M114`), in either firmware's format.
    pub position: Option<Position>,
}

/// A command sent whose answer is still to be read.
#[derive(Debug)]
struct InFlight {
    number: u64,
    command: String,
    limit: Duration,
    deadline: Instant,
    /// The line the printer asked for again, to send once it acknowledges the bad one.
    resend: Option<u64>,
    resends: u32,
    error: Option<String>,
    position: Option<Position>,
    /// When it was sent.
    sent: Instant,
    /// How many `wait` lines (the printer idle) came while it was in flight, later than
    /// [`IDLE_GRACE`] after it was sent.
    idle_reports: u32,
}

impl InFlight {
    fn new(number: u64, command: &str, limit: Duration) -> Self {
        Self {
            number,
            command: command.to_owned(),
            limit,
            deadline: Instant::now() + limit,
            resend: None,
            resends: 0,
            error: None,
            position: None,
            sent: Instant::now(),
            idle_reports: 0,
        }
    }
}

/// An async driver for a Marlin printer over any byte transport (a serial port, a pseudo-
/// terminal, an in-memory pipe in tests): numbered, checksummed lines, one command in flight,
/// `Resend` handled, keep-alives (`busy`) tolerated, an idle printer's `wait` taken as a lost
/// answer, errors and halts surfaced to the caller, and every wait bounded by
/// [`MarlinSettings`] (in tokio's time, which is platform time on hardware).
///
/// `ok` means a move was *queued*; [`Marlin::finish_moves`] (`M400`) is the arrival barrier.
///
/// # Cancel safety
///
/// Every method is cancel safe: the answer to a command whose future was dropped after it was
/// sent is read (within its time limit) before the next command goes out, and a partly read
/// line is kept for the next read.
#[derive(Debug)]
pub struct Marlin<T> {
    stream: BufReader<T>,
    settings: MarlinSettings,
    next_number: u64,
    in_flight: Option<InFlight>,
    partial: Vec<u8>,
    halted: Option<String>,
}

impl<T: AsyncRead + AsyncWrite + Unpin> Marlin<T> {
    /// Starts talking to a printer over `transport`: lets the board boot (until the line is
    /// quiet for [`MarlinSettings::boot_quiet`] or the printer says `wait`), then resets the line
    /// numbers (`M110 N0`) — all within [`MarlinSettings::boot_timeout`], as boards really start:
    /// silent for seconds (a bootloader, a slow SD card), the `start` banner late or never,
    /// garbage (a wrong baud rate), `M110` echoed or refused before the banner. `M110` is sent
    /// again after each `start` and whenever [`HANDSHAKE_RETRY`] passes without its `ok`; after
    /// the boot time it still has [`MarlinSettings::silence`] to be answered.
    ///
    /// # Errors
    ///
    /// [`MarlinError::NoHandshake`] (naming the last line heard) when the printer does not
    /// acknowledge `M110` within the boot time; [`MarlinError::Halted`], or the transport's
    /// failure.
    pub async fn connect(transport: T, settings: MarlinSettings) -> Result<Self, MarlinError> {
        let mut marlin = Self {
            stream: BufReader::new(transport),
            settings,
            next_number: 0,
            in_flight: None,
            partial: Vec::new(),
            halted: None,
        };
        marlin.handshake().await?;
        Ok(marlin)
    }

    /// The settings it was made with.
    pub fn settings(&self) -> &MarlinSettings {
        &self.settings
    }

    /// Homes every axis (`G28`), then sets absolute coordinates (`G90`).
    ///
    /// # Errors
    ///
    /// [`MarlinError`] naming the printer and the command.
    pub async fn home(&mut self) -> Result<(), MarlinError> {
        self.command("G28").await?;
        self.use_absolute_coordinates().await
    }

    /// Sets absolute coordinates (`G90`): [`Marlin::move_to`]'s targets are positions, not
    /// offsets.
    ///
    /// # Errors
    ///
    /// [`MarlinError`] naming the printer and the command.
    pub async fn use_absolute_coordinates(&mut self) -> Result<(), MarlinError> {
        self.command("G90").await.map(drop)
    }

    /// Queues a straight move of the head to `[x, y, z]` millimetres at `feed` mm/s (`G1`,
    /// absolute coordinates as after [`Marlin::home`]); returns once the printer accepted it,
    /// not when the head arrives.
    ///
    /// # Errors
    ///
    /// [`MarlinError`]; a non-finite coordinate or feed is an
    /// [`MarlinError::InvalidCommand`].
    pub async fn move_to(&mut self, [x, y, z]: [f64; 3], feed: f64) -> Result<(), MarlinError> {
        let command = format!("G1 X{x:.3} Y{y:.3} Z{z:.3} F{:.0}", feed * 60.0);
        if ![x, y, z, feed].iter().all(|v| v.is_finite()) || feed <= 0.0 {
            return Err(MarlinError::InvalidCommand { command });
        }
        self.command(&command).await.map(drop)
    }

    /// Waits until every queued move has finished (`M400`).
    ///
    /// # Errors
    ///
    /// [`MarlinError`], [`MarlinError::Timeout`] after [`MarlinSettings::motion_timeout`].
    pub async fn finish_moves(&mut self) -> Result<(), MarlinError> {
        self.command("M400").await.map(drop)
    }

    /// The head's position (`M114`), in stock Marlin's format or the VirtualPrinter's. Marlin
    /// 2 reports the planned position: call [`Marlin::finish_moves`] first for where the head
    /// is.
    ///
    /// # Errors
    ///
    /// [`MarlinError`], [`MarlinError::NoPosition`] when the answer holds none.
    pub async fn position(&mut self) -> Result<Position, MarlinError> {
        let answer = self.command("M114").await?;
        answer.position.ok_or_else(|| MarlinError::NoPosition {
            printer: self.settings.name.clone(),
            command: "M114".into(),
        })
    }

    /// Stops every move at once, dropping the queued ones (`M410`): what to send at shutdown.
    ///
    /// `M410` goes out at once, without a line number, even while a command waits for its
    /// answer (an `M400` waiting for a long move): Marlin's emergency parser acts on it as it
    /// arrives. Then the waiting command's answer and `M410`'s own are read, within
    /// [`MarlinSettings::command_timeout`]; what the waiting command answered is not reported.
    ///
    /// # Errors
    ///
    /// [`MarlinError`]: the line failed, the printer halted, or the answers did not come in
    /// time (a firmware without the emergency parser finishes the waiting command first).
    pub async fn quick_stop(&mut self) -> Result<(), MarlinError> {
        let answers = if self.in_flight.is_some() { 2 } else { 1 };
        self.write(b"M410\n").await?;
        let limit = self.settings.command_timeout;
        self.in_flight = Some(InFlight::new(self.next_number, "M410", limit));
        let stopped = async {
            for _ in 0..answers {
                loop {
                    match Reply::parse(&self.next_line().await?) {
                        Reply::Ok { .. } => break,
                        Reply::Halted(message) => {
                            return Err(MarlinError::Halted {
                                printer: self.settings.name.clone(),
                                message,
                            });
                        }
                        _ => {}
                    }
                }
            }
            Ok(())
        };
        let result = stopped.await;
        self.in_flight = None;
        result
    }

    /// Sends `line` as it is — without a line number or checksum — and waits for no answer: for
    /// a firmware's out-of-band lines, such as the VirtualPrinter's `!!DEBUG:` commands. Earlier
    /// commands' answers are read first.
    ///
    /// # Errors
    ///
    /// [`MarlinError::InvalidCommand`] for a line holding a line break or a non-ASCII
    /// character; [`MarlinError::Io`] when it cannot be written.
    pub async fn send_unnumbered(&mut self, line: &str) -> Result<(), MarlinError> {
        if line.contains(|c: char| !c.is_ascii() || c.is_ascii_control()) {
            return Err(MarlinError::InvalidCommand {
                command: line.to_owned(),
            });
        }
        if self.in_flight.is_some() {
            let _earlier = self.answer().await;
        }
        self.write(format!("{line}\n").as_bytes()).await
    }

    /// Sends `command` as the next numbered line and waits for its `ok`, sending it again when
    /// the printer asks; returns what came with it.
    ///
    /// # Errors
    ///
    /// [`MarlinError`] naming the printer and the command: the printer's own error, a halt, a
    /// restart, silence, a time limit, a resend storm, or the transport's failure.
    pub async fn command(&mut self, command: &str) -> Result<Answer, MarlinError> {
        if self.in_flight.is_some() {
            // A dropped command's answer comes first; its outcome was nobody's to see.
            let _earlier = self.answer().await;
        }
        if let Some(message) = &self.halted {
            return Err(MarlinError::Halted {
                printer: self.settings.name.clone(),
                message: message.clone(),
            });
        }
        let number = self.next_number;
        let line = numbered_line(number, command)?;
        let limit = if matches!(command.split_whitespace().next(), Some("G28" | "M400")) {
            self.settings.motion_timeout
        } else {
            self.settings.command_timeout
        };
        self.next_number += 1;
        self.in_flight = Some(InFlight::new(number, command, limit));
        self.write(&line).await?;
        self.answer().await
    }

    /// Reads until the command in flight is answered.
    async fn answer(&mut self) -> Result<Answer, MarlinError> {
        let result = self.read_answer().await;
        self.in_flight = None;
        result
    }

    async fn read_answer(&mut self) -> Result<Answer, MarlinError> {
        loop {
            let line = self.next_line().await?;
            let printer = self.settings.name.clone();
            let Some(sent) = self.in_flight.as_mut() else {
                return Ok(Answer::default());
            };
            match Reply::parse(&line) {
                Reply::Ok { position } => {
                    if let Some(number) = sent.resend.take() {
                        // This `ok` acknowledges the line that was refused; now send it again.
                        let line = numbered_line(number, &sent.command)?;
                        sent.number = number;
                        self.next_number = number + 1;
                        self.write(&line).await?;
                        continue;
                    }
                    if let Some(message) = sent.error.take() {
                        return Err(MarlinError::Printer {
                            printer,
                            command: sent.command.clone(),
                            message,
                        });
                    }
                    return Ok(Answer {
                        position: position.or(sent.position),
                    });
                }
                Reply::Resend(number) => {
                    sent.resends += 1;
                    if sent.resends > self.settings.max_resends {
                        return Err(MarlinError::ResendStorm {
                            printer,
                            command: sent.command.clone(),
                            resends: sent.resends,
                        });
                    }
                    // The error that came with it was about the line, not the command.
                    sent.error = None;
                    sent.resend = Some(number);
                }
                Reply::Position(position) => sent.position = Some(position),
                Reply::Error(message) => sent.error = Some(message),
                Reply::Halted(message) => {
                    self.halted = Some(message.clone());
                    return Err(MarlinError::Halted { printer, message });
                }
                Reply::Start => {
                    self.next_number = 0;
                    return Err(MarlinError::Restarted {
                        printer,
                        command: sent.command.clone(),
                    });
                }
                Reply::Wait => {
                    // `wait` comes only from an idle printer. Those read just after sending were
                    // on their way before the command arrived; two later ones mean its answer
                    // was lost.
                    if sent.sent.elapsed() >= IDLE_GRACE {
                        sent.idle_reports += 1;
                    }
                    if sent.idle_reports >= 2 {
                        return Err(MarlinError::LostAnswer {
                            printer,
                            command: sent.command.clone(),
                        });
                    }
                }
                Reply::Busy | Reply::Other => {}
            }
        }
    }

    /// The next line for the command in flight, within its deadline and the silence limit.
    async fn next_line(&mut self) -> Result<String, MarlinError> {
        let (command, limit, deadline) = self.in_flight.as_ref().map_or_else(
            || (String::new(), Duration::ZERO, Instant::now()),
            |sent| (sent.command.clone(), sent.limit, sent.deadline),
        );
        let silence = self.settings.silence;
        let now = Instant::now();
        let printer = self.settings.name.clone();
        let timeout = |command| MarlinError::Timeout {
            printer: printer.clone(),
            command,
            seconds: limit.as_secs_f64(),
        };
        if now >= deadline {
            return Err(timeout(command));
        }
        let wait = silence.min(deadline - now);
        let read = line_by(&mut self.stream, &mut self.partial, MAX_LINE, now + wait);
        read.await.map_err(|unread| match unread {
            Unread::Closed => MarlinError::Closed {
                printer: self.settings.name.clone(),
                command,
            },
            Unread::Failed(source) => MarlinError::Io {
                printer: self.settings.name.clone(),
                source,
            },
            Unread::TimedOut if wait < silence => timeout(command),
            Unread::TimedOut => MarlinError::Silent {
                printer: self.settings.name.clone(),
                command,
                seconds: silence.as_secs_f64(),
            },
        })
    }

    /// Lets the board boot and resets the line numbers, by `boot_timeout` (see
    /// [`Marlin::connect`]).
    async fn handshake(&mut self) -> Result<(), MarlinError> {
        let booted = Instant::now() + self.settings.boot_timeout;
        let mut last_heard = self.let_boot(booted).await?;
        // However short the boot time, `M110` has as long to be answered as any command has
        // before the printer counts as silent.
        let until = booted.max(Instant::now() + self.settings.silence);
        loop {
            let now = Instant::now();
            if now >= until {
                // Garbage with no line end (a wrong baud rate) is what was heard, too.
                let unended = (!self.partial.is_empty())
                    .then(|| String::from_utf8_lossy(&self.partial).into_owned());
                return Err(MarlinError::NoHandshake {
                    printer: self.settings.name.clone(),
                    seconds: self.settings.boot_timeout.as_secs_f64(),
                    last_heard: last_heard.or(unended),
                });
            }
            self.write(&numbered_line(0, HANDSHAKE)?).await?;
            let window = HANDSHAKE_RETRY.min(until - now);
            match self.handshake_answer(now + window, &mut last_heard).await? {
                Handshake::Acknowledged => {
                    self.next_number = 1;
                    return Ok(());
                }
                Handshake::Started => {
                    if let Some(heard) = self.let_boot(until.max(booted)).await? {
                        last_heard = Some(heard);
                    }
                }
                Handshake::Unanswered => {}
            }
        }
    }

    /// Reads until `M110`'s `ok`, a restart, or `until`; notes the last line heard.
    async fn handshake_answer(
        &mut self,
        until: Instant,
        last_heard: &mut Option<String>,
    ) -> Result<Handshake, MarlinError> {
        loop {
            let Ok(line) = tokio::time::timeout_at(until, self.read_line()).await else {
                return Ok(Handshake::Unanswered);
            };
            let line = self.boot_line(line)?;
            let reply = Reply::parse(&line);
            if !line.trim().is_empty() {
                *last_heard = Some(line);
            }
            match reply {
                Reply::Ok { .. } => return Ok(Handshake::Acknowledged),
                Reply::Start => return Ok(Handshake::Started),
                // Refused (a garbled line, or lines counted from elsewhere): send it again.
                Reply::Resend(_) => return Ok(Handshake::Unanswered),
                Reply::Halted(message) => {
                    self.halted = Some(message.clone());
                    return Err(MarlinError::Halted {
                        printer: self.settings.name.clone(),
                        message,
                    });
                }
                _ => {}
            }
        }
    }

    /// Reads boot lines until the line is quiet for `boot_quiet`, the printer says `wait`, or
    /// `until`: the last non-empty line heard, if any.
    async fn let_boot(&mut self, until: Instant) -> Result<Option<String>, MarlinError> {
        let mut last_heard = None;
        loop {
            let now = Instant::now();
            if now >= until {
                return Ok(last_heard);
            }
            let quiet = self.settings.boot_quiet.min(until - now);
            let Ok(line) = tokio::time::timeout(quiet, self.read_line()).await else {
                return Ok(last_heard);
            };
            let line = self.boot_line(line)?;
            let reply = Reply::parse(&line);
            if !line.trim().is_empty() {
                last_heard = Some(line);
            }
            if reply == Reply::Wait {
                return Ok(last_heard);
            }
        }
    }

    /// A line read during start-up, or the error that the line closed or failed.
    fn boot_line(&self, line: std::io::Result<Option<String>>) -> Result<String, MarlinError> {
        let printer = self.settings.name.clone();
        match line {
            Ok(Some(line)) => Ok(line),
            Ok(None) => Err(MarlinError::Closed {
                printer,
                command: "start-up".into(),
            }),
            Err(source) => Err(MarlinError::Io { printer, source }),
        }
    }

    /// The next line (see [`read_line`]). Cancel safe.
    async fn read_line(&mut self) -> std::io::Result<Option<String>> {
        read_line(&mut self.stream, &mut self.partial, MAX_LINE).await
    }

    async fn write(&mut self, line: &[u8]) -> Result<(), MarlinError> {
        let stream = self.stream.get_mut();
        let written = async {
            stream.write_all(line).await?;
            stream.flush().await
        };
        written.await.map_err(|source| MarlinError::Io {
            printer: self.settings.name.clone(),
            source,
        })
    }
}
