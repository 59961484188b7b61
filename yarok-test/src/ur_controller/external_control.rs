//! The fake controller running yarok's streaming program
//! ([`yarok_hw::ur::external_control`]) as a controller would: it connects back to the address
//! the program names, reads its messages, and each controller step (2 ms on e-Series, 8 ms on
//! CB3) moves the arm toward the point the interpolation has reached, each joint capped at the
//! program's speed limits; it stops the arm and ends when no message comes within the
//! watchdog, when the connection closes, when asked to stop, when another script arrives, or
//! when the arm stops for safety or loses power. The parameters come from the program's own
//! text, so a program that says other limits is run with them.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use tokio::io::AsyncReadExt;
use tokio::net::TcpStream;
use yarok_hw::ur::external_control::{FIRST_MESSAGE_SECONDS, MESSAGE_INTEGERS, Message, Mode};

use super::motion::ArmCommand;
use super::{Profile, Shared};

/// What the fake read from a streaming program's text.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StreamProgram {
    host: String,
    port: u16,
    max_speed: [f64; 6],
}

impl StreamProgram {
    /// The program `text` is, if it is yarok's streaming program.
    pub(super) fn parse(text: &str) -> Option<Self> {
        if !text.starts_with("def yarok_stream():") {
            return None;
        }
        let opening = text.split("socket_open(\"").nth(1)?;
        let (host, rest) = opening.split_once('"')?;
        let port = rest
            .trim_start_matches([',', ' '])
            .split(',')
            .next()?
            .trim()
            .parse()
            .ok()?;
        let speeds = text.split("max_speed = [").nth(1)?.split(']').next()?;
        let speeds: Vec<f64> = speeds
            .split(',')
            .map(|speed| speed.trim().parse())
            .collect::<Result<_, _>>()
            .ok()?;
        Some(Self {
            host: host.to_owned(),
            port,
            max_speed: speeds.try_into().ok()?,
        })
    }
}

/// A streaming program's run, as the fake saw it.
#[derive(Debug, Clone, PartialEq)]
pub enum ProgramEvent {
    /// It connected back to its sender.
    Started,
    /// A message arrived.
    Message(Message),
    /// A controller step commanded the joints to `q`.
    Step([f64; 6]),
    /// It stopped the arm and ended, for the reason given.
    Ended(String),
}

impl Shared {
    fn record(&self, event: ProgramEvent) {
        self.program_events
            .lock()
            .unwrap()
            .push((Instant::now(), event));
    }

    /// Why the arm cannot be servoed now, if it cannot.
    fn halted(&self) -> Option<String> {
        let arm = self.arm.lock().unwrap();
        if arm.safety != "NORMAL" {
            return Some(format!("the arm stopped for safety ({})", arm.safety));
        }
        (arm.robot_mode != "RUNNING").then(|| format!("the arm is {}", arm.robot_mode))
    }
}

/// Runs `program` until it ends or `aborted` is set (another script arrived).
pub(super) async fn run_program(
    shared: Arc<Shared>,
    program: StreamProgram,
    aborted: Arc<AtomicBool>,
) {
    let step = match shared.profile {
        Profile::ESeries => 0.002,
        Profile::Cb3 => 0.008,
    };
    let connecting = TcpStream::connect((program.host.as_str(), program.port));
    let stream = match tokio::time::timeout(Duration::from_secs(1), connecting).await {
        Ok(Ok(stream)) => stream,
        _ => {
            shared.record(ProgramEvent::Ended(format!(
                "cannot connect back to {}:{}",
                program.host, program.port
            )));
            return;
        }
    };
    shared.record(ProgramEvent::Started);
    let (mut reader, _writer) = stream.into_split();
    let mut commanded = shared.motion.lock().unwrap().state().q;
    let (mut from, mut goal, mut period, mut elapsed) = (commanded, commanded, 1.0, 0.0);
    let mut deadline = Instant::now() + Duration::from_secs_f64(FIRST_MESSAGE_SECONDS);
    let mut watchdog = Duration::from_secs_f64(FIRST_MESSAGE_SECONDS);
    let mut ticks = tokio::time::interval(Duration::from_secs_f64(step));
    ticks.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    let mut bytes = [0u8; 4 * MESSAGE_INTEGERS];
    let mut filled = 0;
    let why = loop {
        tokio::select! {
            _ = ticks.tick() => {
                if aborted.load(Ordering::Relaxed) || shared.closed.load(Ordering::Relaxed) {
                    break "another program replaced it".to_owned();
                }
                if let Some(halted) = shared.halted() {
                    break halted;
                }
                if Instant::now() > deadline {
                    break format!(
                        "no message within its watchdog ({} s)",
                        watchdog.as_secs_f64()
                    );
                }
                elapsed += step;
                let share = (elapsed / period).min(1.0);
                for i in 0..6 {
                    let most = program.max_speed[i] * step;
                    let delta = from[i] + (goal[i] - from[i]) * share - commanded[i];
                    commanded[i] += delta.clamp(-most, most);
                }
                shared.motion.lock().unwrap().command(ArmCommand::Servo {
                    to: commanded,
                    seconds: step,
                });
                shared.record(ProgramEvent::Step(commanded));
            }
            read = reader.read(&mut bytes[filled..]) => match read {
                Ok(0) | Err(_) => break "its connection closed".to_owned(),
                Ok(count) => {
                    filled += count;
                    if filled < bytes.len() {
                        continue;
                    }
                    filled = 0;
                    let Some(message) = Message::from_bytes(&bytes) else {
                        break "a message of an unknown mode".to_owned();
                    };
                    shared.record(ProgramEvent::Message(message));
                    watchdog = message.watchdog;
                    deadline = Instant::now() + watchdog;
                    match message.mode {
                        Mode::Stop => break "asked to stop".to_owned(),
                        Mode::Servo => {
                            (from, goal, period, elapsed) = (commanded, message.q, message.period, 0.0);
                        }
                        Mode::KeepAlive => {}
                    }
                }
            }
        }
    };
    shared.motion.lock().unwrap().command(ArmCommand::Stop);
    shared.record(ProgramEvent::Ended(why));
}

#[cfg(test)]
mod tests {
    use super::*;
    use yarok_hw::ur::external_control::{ProgramSettings, program};

    #[test]
    fn the_fake_reads_its_parameters_from_the_programs_text() {
        let text = program(&ProgramSettings {
            host: "127.0.3.4".into(),
            port: 41234,
            max_speed: [3.0, 3.0, 3.0, 2.0, 2.0, 1.5],
            stop_deceleration: 4.0,
            lookahead: 0.1,
            gain: 300.0,
        });
        assert_eq!(
            StreamProgram::parse(&text),
            Some(StreamProgram {
                host: "127.0.3.4".into(),
                port: 41234,
                max_speed: [3.0, 3.0, 3.0, 2.0, 2.0, 1.5],
            })
        );
        assert_eq!(StreamProgram::parse("def yarok_move():\nend"), None);
    }
}
