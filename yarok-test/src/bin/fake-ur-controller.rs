//! The project's fake UR controller as a process of its own, for tests in other languages (the
//! Python package's real-robot test): an e-Series UR5e (the linear stand-in arm) with a 2F-85 on
//! its URCap socket, on a loopback address of its own.
//!
//! Prints `host ADDRESS` once it listens, then a line for everything clients ask, as they ask
//! it: `script SECONDS LINE` for each URScript line (when it arrived, from the fake's start; a
//! program's lines joined by `\n`), `gripper COMMAND` for each gripper `SET`, and for yarok's
//! streaming program `program SECONDS started`, `message SECONDS MODE PERIOD Q0 … Q5` for each
//! message it reads (`Servo`, `KeepAlive`, `Stop`) and `program SECONDS ended WHY`. Takes faults
//! on its standard input, a line each: `protective stop`, `emergency stop`, `power off`, `mute
//! gripper`, `late dashboard SECONDS`. Ends when its standard input closes.

use std::io::{BufRead, Write};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::Duration;

use yarok_test::ur_controller::{FakeController, Profile, ProgramEvent};

fn main() {
    let started = std::time::Instant::now();
    let fake = FakeController::start(Profile::ESeries);
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "host {}", fake.host);
    let _ = out.flush();
    let (told, stdin_lines) = channel::<Option<String>>();
    std::thread::spawn(move || {
        for line in std::io::stdin().lock().lines().map_while(Result::ok) {
            let _ = told.send(Some(line));
        }
        let _ = told.send(None);
    });
    let (mut scripts, mut commands, mut events) = (0, 0, 0);
    loop {
        let ended = match stdin_lines.recv_timeout(Duration::from_millis(10)) {
            Err(RecvTimeoutError::Timeout) => false,
            Ok(Some(fault)) => {
                match fault.trim() {
                    "protective stop" => fake.protective_stop(Duration::ZERO),
                    "emergency stop" => fake.emergency_stop(),
                    "power off" => fake.power_off(),
                    "mute gripper" => fake.mute_gripper(),
                    other => match other
                        .strip_prefix("late dashboard ")
                        .and_then(|seconds| seconds.parse::<f64>().ok())
                        .and_then(|seconds| Duration::try_from_secs_f64(seconds).ok())
                    {
                        Some(late) => fake.set_dashboard_delay(late),
                        None => {
                            let _ = writeln!(out, "error unknown fault {other:?}");
                        }
                    },
                }
                false
            }
            Ok(None) | Err(RecvTimeoutError::Disconnected) => true,
        };
        let seen = fake.scripts_arrived();
        for (arrived, line) in &seen[scripts..] {
            let at = arrived.duration_since(started).as_secs_f64();
            let _ = writeln!(out, "script {at:.6} {}", line.replace('\n', "\\n"));
        }
        scripts = seen.len();
        let happened = fake.program_events();
        for (at, event) in &happened[events..] {
            let at = at.duration_since(started).as_secs_f64();
            let _ = match event {
                ProgramEvent::Started => writeln!(out, "program {at:.6} started"),
                ProgramEvent::Message(message) => {
                    let q: Vec<String> = message.q.iter().map(|v| format!("{v:.6}")).collect();
                    writeln!(
                        out,
                        "message {at:.6} {:?} {:.6} {}",
                        message.mode,
                        message.period,
                        q.join(" ")
                    )
                }
                ProgramEvent::Step(_) => Ok(()),
                ProgramEvent::Ended(why) => writeln!(out, "program {at:.6} ended {why}"),
            };
        }
        events = happened.len();
        let asked = fake.fingers().commands;
        for command in &asked[commands..] {
            let _ = writeln!(out, "gripper {}", command.trim_end());
        }
        commands = asked.len();
        let _ = out.flush();
        if ended {
            break;
        }
    }
}
