//! External control: one URScript program runs on the controller for a whole stream of joint
//! targets, reading them from a socket this side listens on, and servoing toward them at the
//! controller's own rate — the way Universal Robots' `ur_client_library` drives an arm (its
//! `external_control.urscript` and reverse interface), rather than a `servoj` program sent per
//! target, each of which a controller compiles anew and which aborts the one before.
//!
//! The program ([`program`]) connects back to `host:port` and reads [`Message`]s of
//! [`MESSAGE_INTEGERS`] big-endian `int32`s:
//!
//! | index | meaning |
//! |---|---|
//! | 0 | the watchdog: milliseconds the program waits for the next message before it stops the arm |
//! | 1 | the [`Mode`]: 0 stop, 1 a new target, 2 keep-alive |
//! | 2 | the target's period, microseconds: the program moves there linearly over it |
//! | 3–8 | the target joints, micro-radians |
//!
//! Each controller step (`get_steptime()`: 2 ms on e-Series, 8 ms on CB3) it commands
//! `servoj` toward the point the interpolation has reached, each joint capped at its speed
//! limit, which the program carries ([`ProgramSettings::max_speed`]): whatever arrives, no step
//! asks more. When no message comes within the watchdog (the sender was killed, the network
//! went down), or the connection closes, or a [`Mode::Stop`] arrives, the program stops the
//! arm (`stopj`) and ends; so does the controller when a new program is sent, or the arm
//! stops for safety. The sender sees the program end as its connection closing.

use std::time::Duration;

use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt};

/// Integers in one message.
pub const MESSAGE_INTEGERS: usize = 9;

/// The scale of the integers: a joint of 1 rad is sent as 1 000 000, a period of 1 s likewise.
pub const MULT: f64 = 1_000_000.0;

/// Seconds the program waits for the first message after it connects.
pub const FIRST_MESSAGE_SECONDS: f64 = 1.0;

/// The socket name the program reads on.
const SOCKET: &str = "yarok_stream";

/// What a message asks of the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(i32)]
pub enum Mode {
    /// Stop the arm and end the program.
    Stop = 0,
    /// Move to a new target over its period.
    Servo = 1,
    /// Nothing new: the watchdog starts again.
    KeepAlive = 2,
}

/// One message to the program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Message {
    /// How long the program waits for the next message before it stops the arm.
    pub watchdog: Duration,
    /// What it asks.
    pub mode: Mode,
    /// The seconds the program moves to the target in.
    pub period: f64,
    /// The target joints (radians).
    pub q: [f64; 6],
}

impl Message {
    /// The message's bytes: [`MESSAGE_INTEGERS`] big-endian `int32`s.
    ///
    /// ```
    /// use std::time::Duration;
    /// use yarok_hw::ur::external_control::{Message, Mode};
    ///
    /// let bytes = Message {
    ///     watchdog: Duration::from_millis(200),
    ///     mode: Mode::Servo,
    ///     period: 0.05,
    ///     q: [1.0, -1.5, 0.0, 0.0, 0.0, 0.000_001],
    /// }
    /// .to_bytes();
    /// assert_eq!(&bytes[..12], &[0, 0, 0, 200, 0, 0, 0, 1, 0, 0, 0xC3, 0x50]);
    /// assert_eq!(&bytes[12..20], &[0, 0x0F, 0x42, 0x40, 0xFF, 0xE9, 0x1C, 0xA0]);
    /// assert_eq!(&bytes[32..], &[0, 0, 0, 1]);
    /// ```
    pub fn to_bytes(&self) -> [u8; 4 * MESSAGE_INTEGERS] {
        let scaled = |value: f64| (value * MULT).round() as i32;
        let millis = i32::try_from(self.watchdog.as_millis()).unwrap_or(i32::MAX);
        let mut integers = [0i32; MESSAGE_INTEGERS];
        integers[0] = millis;
        integers[1] = self.mode as i32;
        integers[2] = scaled(self.period);
        for (slot, value) in integers[3..].iter_mut().zip(self.q) {
            *slot = scaled(value);
        }
        let mut bytes = [0u8; 4 * MESSAGE_INTEGERS];
        for (chunk, integer) in bytes.chunks_exact_mut(4).zip(integers) {
            chunk.copy_from_slice(&integer.to_be_bytes());
        }
        bytes
    }

    /// The message `bytes` hold, as the program reads it; `None` for an unknown mode.
    pub fn from_bytes(bytes: &[u8; 4 * MESSAGE_INTEGERS]) -> Option<Self> {
        let mut integers = [0i32; MESSAGE_INTEGERS];
        for (integer, chunk) in integers.iter_mut().zip(bytes.chunks_exact(4)) {
            *integer = i32::from_be_bytes([chunk[0], chunk[1], chunk[2], chunk[3]]);
        }
        let mode = match integers[1] {
            0 => Mode::Stop,
            1 => Mode::Servo,
            2 => Mode::KeepAlive,
            _ => return None,
        };
        Some(Self {
            watchdog: Duration::from_millis(u64::try_from(integers[0]).unwrap_or(0)),
            mode,
            period: f64::from(integers[2]) / MULT,
            q: std::array::from_fn(|i| f64::from(integers[3 + i]) / MULT),
        })
    }
}

/// What the program is written with.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramSettings {
    /// The address the controller reaches the sender at.
    pub host: String,
    /// The port the sender listens on.
    pub port: u16,
    /// Each joint's speed limit (rad/s): no controller step asks more.
    pub max_speed: [f64; 6],
    /// The deceleration (rad/s²) the program stops the arm with.
    pub stop_deceleration: f64,
    /// `servoj`'s smoothing (seconds, 0.03–0.2) and gain (100–2000).
    pub lookahead: f64,
    /// See `lookahead`.
    pub gain: f64,
}

/// The program's text, to send over the secondary interface.
///
/// ```
/// use yarok_hw::ur::external_control::{ProgramSettings, program};
///
/// let text = program(&ProgramSettings {
///     host: "192.168.1.5".into(),
///     port: 50002,
///     max_speed: [3.14; 6],
///     stop_deceleration: 6.0,
///     lookahead: 0.1,
///     gain: 300.0,
/// });
/// assert!(text.starts_with("def yarok_stream():\n"));
/// assert!(text.contains(r#"socket_open("192.168.1.5", 50002, "yarok_stream")"#));
/// assert!(text.ends_with("end\n"));
/// ```
pub fn program(settings: &ProgramSettings) -> String {
    let ProgramSettings {
        host,
        port,
        max_speed,
        stop_deceleration,
        lookahead,
        gain,
    } = settings;
    let speeds: Vec<String> = max_speed.iter().map(|v| format!("{v:.6}")).collect();
    let speeds = speeds.join(", ");
    let target: Vec<String> = (0..6)
        .map(|i| format!("message[{}] / MULT", 4 + i))
        .collect();
    let target = target.join(", ");
    let count = MESSAGE_INTEGERS;
    let first = FIRST_MESSAGE_SECONDS;
    let stop = super::script::stopj(*stop_deceleration);
    format!(
        "def yarok_stream():
  MULT = {MULT:.1}
  STEP = get_steptime()
  max_speed = [{speeds}]
  global commanded = get_actual_joint_positions()
  global start_q = commanded
  global goal_q = commanded
  global period = 1.0
  global elapsed = 0.0
  global streaming = True
  thread servo_thread():
    while streaming:
      enter_critical
      elapsed = elapsed + STEP
      share = elapsed / period
      if share > 1.0:
        share = 1.0
      end
      i = 0
      while i < 6:
        delta = start_q[i] + (goal_q[i] - start_q[i]) * share - commanded[i]
        most = max_speed[i] * STEP
        if delta > most:
          delta = most
        elif delta < -most:
          delta = -most
        end
        commanded[i] = commanded[i] + delta
        i = i + 1
      end
      q = commanded
      exit_critical
      servoj(q, t=STEP, lookahead_time={lookahead}, gain={gain})
    end
  end
  if not socket_open(\"{host}\", {port}, \"{SOCKET}\"):
    textmsg(\"yarok: cannot connect back to {host}:{port}\")
    halt
  end
  servo = run servo_thread()
  timeout = {first:.1}
  while streaming:
    message = socket_read_binary_integer({count}, \"{SOCKET}\", timeout)
    if message[0] != {count}:
      textmsg(\"yarok: no target within the watchdog, or the connection closed: stopping\")
      streaming = False
    elif message[2] == {stop_mode}:
      streaming = False
    else:
      timeout = message[1] / 1000.0
      if message[2] == {servo_mode}:
        enter_critical
        start_q = commanded
        goal_q = [{target}]
        period = message[3] / MULT
        elapsed = 0.0
        exit_critical
      end
    end
  end
  kill servo
  {stop}
  socket_close(\"{SOCKET}\")
end
",
        stop_mode = Mode::Stop as i32,
        servo_mode = Mode::Servo as i32,
    )
}

/// What went wrong streaming to the program.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExternalControlError {
    /// Writing failed.
    #[error("the streaming program's connection: {0}")]
    Io(#[from] std::io::Error),
    /// A message could not be written in time (the network or the controller stalled).
    #[error("the streaming program took no message within {seconds} s")]
    Stalled {
        /// The time limit.
        seconds: f64,
    },
}

/// The sending side of the program's connection, over any transport: a TCP stream the
/// program opened to the listener, or a test's duplex.
///
/// ```
/// use std::time::Duration;
/// use tokio::io::AsyncReadExt;
/// use yarok_hw::ur::external_control::{ExternalControl, Message, Mode, MESSAGE_INTEGERS};
///
/// # #[tokio::main(flavor = "current_thread")]
/// # async fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let (ours, mut program) = tokio::io::duplex(1024);
/// let mut control = ExternalControl::new(ours, Duration::from_millis(200), Duration::from_secs(1));
/// control.servo([0.1; 6], 0.05).await?;
/// let mut bytes = [0u8; 4 * MESSAGE_INTEGERS];
/// program.read_exact(&mut bytes).await?;
/// let message = Message::from_bytes(&bytes).unwrap();
/// assert_eq!((message.mode, message.period, message.q), (Mode::Servo, 0.05, [0.1; 6]));
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct ExternalControl<T> {
    transport: T,
    watchdog: Duration,
    write_within: Duration,
    last: [f64; 6],
}

impl<T: AsyncRead + AsyncWrite + Unpin> ExternalControl<T> {
    /// Streams over `transport`: each message asks the program to stop the arm when the next
    /// does not come within `watchdog`; each is written within `write_within`.
    pub fn new(transport: T, watchdog: Duration, write_within: Duration) -> Self {
        Self {
            transport,
            watchdog,
            write_within,
            last: [0.0; 6],
        }
    }

    /// Asks the program to move to `q` over `period` seconds.
    ///
    /// # Errors
    ///
    /// [`ExternalControlError`] when the message cannot be written in time.
    pub async fn servo(&mut self, q: [f64; 6], period: f64) -> Result<(), ExternalControlError> {
        self.last = q;
        self.send(Mode::Servo, period, q).await
    }

    /// Tells the program the sender is alive: its watchdog starts again.
    ///
    /// # Errors
    ///
    /// As [`ExternalControl::servo`].
    pub async fn keep_alive(&mut self) -> Result<(), ExternalControlError> {
        self.send(Mode::KeepAlive, 0.0, self.last).await
    }

    /// Asks the program to stop the arm and end.
    ///
    /// # Errors
    ///
    /// As [`ExternalControl::servo`].
    pub async fn stop(&mut self) -> Result<(), ExternalControlError> {
        self.send(Mode::Stop, 0.0, self.last).await
    }

    async fn send(
        &mut self,
        mode: Mode,
        period: f64,
        q: [f64; 6],
    ) -> Result<(), ExternalControlError> {
        let bytes = Message {
            watchdog: self.watchdog,
            mode,
            period,
            q,
        }
        .to_bytes();
        tokio::time::timeout(self.write_within, self.transport.write_all(&bytes))
            .await
            .map_err(|_| ExternalControlError::Stalled {
                seconds: self.write_within.as_secs_f64(),
            })??;
        Ok(())
    }

    /// Resolves when the program closes its connection: it ended (it stopped the arm, or the
    /// controller stopped it). What the program writes is read and dropped.
    ///
    /// # Cancel safety
    ///
    /// Cancel safe: nothing read is needed.
    pub async fn ended(&mut self) -> std::io::Result<()> {
        let mut scratch = [0u8; 64];
        loop {
            if self.transport.read(&mut scratch).await? == 0 {
                return Ok(());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_message_reads_back_to_itself_within_a_microradian() {
        let message = Message {
            watchdog: Duration::from_millis(150),
            mode: Mode::Servo,
            period: 0.008,
            q: [3.25, -2.0, 0.5, -0.000_000_4, 6.1234567, -6.1234567],
        };
        let back = Message::from_bytes(&message.to_bytes()).unwrap();
        assert_eq!(back.watchdog, message.watchdog);
        assert_eq!(back.mode, Mode::Servo);
        assert_eq!(back.period, 0.008);
        for (a, b) in back.q.iter().zip(message.q) {
            assert!((a - b).abs() <= 0.5e-6, "{a} {b}");
        }
        let mut unknown = message.to_bytes();
        unknown[7] = 7;
        assert_eq!(Message::from_bytes(&unknown), None);
    }

    #[test]
    fn the_program_carries_its_limits_and_stops_the_arm_when_it_ends() {
        let text = program(&ProgramSettings {
            host: "10.0.0.2".into(),
            port: 50002,
            max_speed: [3.25, 3.25, 3.25, 3.0, 3.0, 3.0],
            stop_deceleration: 6.5,
            lookahead: 0.1,
            gain: 300.0,
        });
        assert!(
            text.contains(
                "max_speed = [3.250000, 3.250000, 3.250000, 3.000000, 3.000000, 3.000000]"
            )
        );
        assert!(
            text.contains("message = socket_read_binary_integer(9, \"yarok_stream\", timeout)")
        );
        assert!(text.contains("servoj(q, t=STEP, lookahead_time=0.1, gain=300)"));
        assert!(text.contains("goal_q = [message[4] / MULT, message[5] / MULT, message[6] / MULT, message[7] / MULT, message[8] / MULT, message[9] / MULT]"));
        let ending = text.rsplit("kill servo").next().unwrap();
        assert_eq!(
            ending,
            "\n  stopj(6.5)\n  socket_close(\"yarok_stream\")\nend\n"
        );
        // Every block the program opens, it closes.
        let opens = text
            .lines()
            .filter(|line| {
                let line = line.trim();
                (line.starts_with("def ")
                    || line.starts_with("thread ")
                    || line.starts_with("while ")
                    || line.starts_with("if "))
                    && line.ends_with(':')
            })
            .count();
        let ends = text.lines().filter(|line| line.trim() == "end").count();
        assert_eq!(opens, ends, "{text}");
    }

    #[tokio::test]
    async fn a_stalled_connection_is_named_within_its_time() {
        let (ours, _program) = tokio::io::duplex(8);
        let mut control =
            ExternalControl::new(ours, Duration::from_millis(200), Duration::from_millis(50));
        let error = control.servo([0.0; 6], 0.05).await.unwrap_err();
        assert_eq!(
            error.to_string(),
            "the streaming program took no message within 0.05 s"
        );
    }

    #[tokio::test]
    async fn the_end_of_the_program_is_its_connection_closing() {
        let (ours, program) = tokio::io::duplex(64);
        let mut control = ExternalControl::new(ours, Duration::from_millis(200), Duration::ZERO);
        drop(program);
        control.ended().await.unwrap();
    }
}
