//! The project's fake UR controller as a process of its own, for tests in other languages (the
//! Python package's real-robot test): an e-Series UR5e (the linear stand-in arm) with a 2F-85 on
//! its URCap socket, on a loopback address of its own.
//!
//! Prints `host ADDRESS` once it listens, then a line for everything clients ask, as they ask
//! it: `script SECONDS LINE` for each URScript line (when it arrived, from the fake's start),
//! `gripper COMMAND` for each gripper `SET`. Ends when
//! its standard input closes.

use std::io::{BufRead, Write};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::Duration;

use yarok_test::ur_controller::{FakeController, Profile};

fn main() {
    let started = std::time::Instant::now();
    let fake = FakeController::start(Profile::ESeries);
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "host {}", fake.host);
    let _ = out.flush();
    let (closed, stdin_closed) = channel::<()>();
    std::thread::spawn(move || {
        for _ in std::io::stdin().lock().lines().map_while(Result::ok) {}
        let _ = closed.send(());
    });
    let (mut scripts, mut commands) = (0, 0);
    loop {
        let ended = match stdin_closed.recv_timeout(Duration::from_millis(10)) {
            Err(RecvTimeoutError::Timeout) => false,
            Ok(()) | Err(RecvTimeoutError::Disconnected) => true,
        };
        let seen = fake.scripts_arrived();
        for (arrived, line) in &seen[scripts..] {
            let at = arrived.duration_since(started).as_secs_f64();
            let _ = writeln!(out, "script {at:.6} {}", line.replace('\n', "\\n"));
        }
        scripts = seen.len();
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
