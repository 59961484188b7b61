//! The fake controller's secondary interface, and the arm's joints moving as scripts ask.

use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Duration;

use tokio::io::{AsyncBufReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

use super::external_control::{StreamProgram, run_program};
use super::motion::{ArmCommand, ArmState};
use super::{Profile, Shared};

/// The numbers of a URScript call `name(…)` in `line` — its list's, then its keywords' — if
/// the line is that call.
fn call(line: &str, name: &str) -> Option<Vec<f64>> {
    let inside = line.trim().strip_prefix(name)?.strip_prefix('(')?;
    let inside = inside.strip_suffix(')')?;
    let numbers = inside
        .split([',', '[', ']', '='])
        .filter_map(|part| part.trim().parse().ok())
        .collect();
    Some(numbers)
}

impl Shared {
    /// Runs one line of URScript — `movej([q…], a=…, v=…)`, `set_tcp(p[…])`,
    /// `movel(p[pose…], a=…, v=…)`, `servoj([q…], t=…, lookahead_time=…, gain=…)`, `stopj(…)`,
    /// `stopl(…)` — unless a safety stop holds the
    /// arm, it is not running (powered off, brakes locked) or the controller is in local
    /// control; other lines (`def`, `end`, …) are kept only.
    pub(super) fn run_script(&self, line: &str) {
        if line.trim().is_empty() {
            return;
        }
        let arrived = std::time::Instant::now();
        self.scripts
            .lock()
            .unwrap()
            .push((arrived, line.to_owned()));
        if !self.runs_scripts() {
            return;
        }
        // A script sent replaces the program running, as on a controller.
        self.end_program();
        let six = |numbers: &[f64]| -> [f64; 6] { std::array::from_fn(|i| numbers[i]) };
        let command = if let Some(numbers) = call(line, "movej")
            && numbers.len() >= 6
        {
            ArmCommand::Joints {
                to: six(&numbers),
                acceleration: numbers.get(6).copied().unwrap_or(1.4),
                speed: numbers.get(7).copied().unwrap_or(1.05),
            }
        } else if let Some(numbers) = call(line, "set_tcp")
            && numbers.len() == 6
        {
            *self.tcp.lock().unwrap() = six(&numbers);
            return;
        } else if let Some(numbers) = call(line, "movel")
            && numbers.len() >= 6
        {
            ArmCommand::Line {
                pose: six(&numbers),
                tcp: *self.tcp.lock().unwrap(),
                acceleration: numbers.get(6).copied().unwrap_or(1.2),
                speed: numbers.get(7).copied().unwrap_or(0.25),
            }
        } else if let Some(numbers) = call(line, "servoj")
            && numbers.len() >= 7
        {
            // `t` is the first keyword: the list's six numbers, then t, lookahead, gain.
            ArmCommand::Servo {
                to: six(&numbers),
                seconds: numbers[6],
            }
        } else if call(line, "stopj").is_some() || call(line, "stopl").is_some() {
            ArmCommand::Stop
        } else {
            return;
        };
        self.motion.lock().unwrap().command(command);
    }

    /// Whether a script sent now runs: not while a safety stop holds the arm, it is not
    /// running or the controller is in local control.
    fn runs_scripts(&self) -> bool {
        let arm = self.arm.lock().unwrap();
        arm.safety == "NORMAL" && arm.robot_mode == "RUNNING" && arm.remote_control
    }

    /// Ends the streaming program running, if one runs.
    pub(super) fn end_program(&self) {
        if let Some(running) = self.running_program.lock().unwrap().take() {
            running.store(true, Ordering::Relaxed);
        }
    }

    /// Runs a program sent whole (`def …():` to `end`): yarok's streaming program as a
    /// controller would; any other, line by line.
    pub(super) fn run_program(self: &Arc<Self>, text: &str) {
        let Some(program) = StreamProgram::parse(text) else {
            for line in text.lines() {
                self.run_script(line);
            }
            return;
        };
        self.scripts
            .lock()
            .unwrap()
            .push((std::time::Instant::now(), text.to_owned()));
        if !self.runs_scripts() {
            return;
        }
        self.end_program();
        let aborted = Arc::new(std::sync::atomic::AtomicBool::new(false));
        *self.running_program.lock().unwrap() = Some(Arc::clone(&aborted));
        tokio::spawn(run_program(Arc::clone(self), program, aborted));
    }

    /// A robot-state packet in the profile's layout.
    fn robot_state(&self) -> Vec<u8> {
        let ArmState {
            q,
            qd,
            target,
            moving,
        } = self.motion.lock().unwrap().state();
        let e_series = self.profile == Profile::ESeries;
        let protective = self.arm.lock().unwrap().safety == "PROTECTIVE_STOP";
        let mode = self.robot_mode();
        let mut body = Vec::new();
        sub_package(&mut body, 0, |out| {
            let micros = self.started.elapsed().as_micros() as u64;
            out.extend(micros.to_be_bytes());
            let powered = mode != 3;
            out.extend([
                1,
                1,
                u8::from(powered),
                0,
                u8::from(protective),
                u8::from(moving),
                0,
            ]);
            out.extend([mode, 0]);
            for value in [1.0f64, 1.0, 1.0] {
                out.extend(value.to_be_bytes());
            }
            if e_series {
                out.push(0);
            }
        });
        sub_package(&mut body, 1, |out| {
            for i in 0..6 {
                for value in [q[i], target[i], qd[i]] {
                    out.extend(value.to_be_bytes());
                }
                for value in [0.5f32, 48.0, 30.0, 30.0] {
                    out.extend(value.to_be_bytes());
                }
                out.push(253);
            }
        });
        sub_package(&mut body, 2, |out| out.extend([0; 32]));
        sub_package(&mut body, 3, |out| {
            out.extend(vec![0; if e_series { 70 } else { 69 }])
        });
        sub_package(&mut body, 4, |out| out.extend([0; 96]));
        sub_package(&mut body, 5, |out| {
            out.extend([0; 24]);
            let (a, d) = if e_series {
                (
                    [0.0, -0.425, -0.3922, 0.0, 0.0, 0.0],
                    [0.1625, 0.0, 0.0, 0.1333, 0.0997, 0.0996],
                )
            } else {
                (
                    [0.0, -0.425, -0.39225, 0.0, 0.0, 0.0],
                    [0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823],
                )
            };
            let alpha = [FRAC_PI_2, 0.0, 0.0, FRAC_PI_2, -FRAC_PI_2, 0.0];
            for values in [[0.0; 6], a, d, alpha] {
                for value in values {
                    out.extend(value.to_be_bytes());
                }
            }
            out.extend([0; 4]);
        });
        sub_package(&mut body, 7, |out| out.extend([0; 56]));
        sub_package(&mut body, 8, |out| {
            out.extend(vec![0; if e_series { 4 } else { 3 }])
        });
        packet(16, &body)
    }

    /// The version message sent on connect.
    fn version_message(&self) -> Vec<u8> {
        let version = self.profile.version();
        let mut body = Vec::new();
        body.extend(0u64.to_be_bytes());
        body.extend([(-2i8) as u8, 3, 9]);
        body.extend(b"URControl");
        body.extend([version.major as u8, version.minor as u8]);
        body.extend((version.bugfix as i32).to_be_bytes());
        body.extend((version.build as i32).to_be_bytes());
        body.extend(b"22-03-2022, 10:33:46");
        packet(20, &body)
    }
}

/// `int32 size, uint8 type, body`.
fn packet(kind: u8, body: &[u8]) -> Vec<u8> {
    let mut out = ((body.len() + 5) as i32).to_be_bytes().to_vec();
    out.push(kind);
    out.extend_from_slice(body);
    out
}

fn sub_package(out: &mut Vec<u8>, kind: u8, content: impl FnOnce(&mut Vec<u8>)) {
    let mut body = Vec::new();
    content(&mut body);
    out.extend(packet(kind, &body));
}

/// One client's secondary session: the version message, then a robot state every 100 ms;
/// script lines run as they come, a program (`def …():` to `end`) once whole.
pub(super) async fn serve_secondary(stream: TcpStream, shared: Arc<Shared>) {
    let drops = shared.drops.load(Ordering::Relaxed);
    let (reader, mut writer) = stream.into_split();
    if writer.write_all(&shared.version_message()).await.is_err() {
        return;
    }
    let mut lines = tokio::io::BufReader::new(reader).lines();
    let mut states = tokio::time::interval(Duration::from_millis(100));
    let mut program: Option<String> = None;
    loop {
        tokio::select! {
            line = lines.next_line() => match (line, program.as_mut()) {
                (Ok(Some(line)), Some(text)) => {
                    text.push('\n');
                    text.push_str(&line);
                    if line == "end" {
                        shared.run_program(&program.take().unwrap_or_default());
                    }
                }
                (Ok(Some(line)), None) if line.starts_with("def ") => program = Some(line),
                (Ok(Some(line)), None) => shared.run_script(&line),
                _ => return,
            },
            _ = states.tick() => {
                if shared.drops.load(Ordering::Relaxed) != drops {
                    return;
                }
                if shared.secondary_mute.load(Ordering::Relaxed) {
                    continue;
                }
                if writer.write_all(&shared.robot_state()).await.is_err() {
                    return;
                }
            }
        }
    }
}
