//! Ctrl-C, SIGTERM and SIGHUP end a run cleanly. Alone in its file, so that the signal reaches
//! no other test's platform (each test file is its own process).

#[allow(dead_code, reason = "each test file uses part of the shared device")]
mod device;

use std::cell::Cell;
use std::rc::Rc;

use device::{Device, Lab, Server};
use yarok_core::BoxError;
use yarok_core::component::{Component, Declaration, Mock, MockBackend};
use yarok_core::runtime::{Platform, Plugin, RuntimeError, World};

struct Empty;
impl Component for Empty {
    fn declaration() -> Declaration {
        Declaration::new("empty").template("<mujoco><worldbody/></mujoco>")
    }
}

/// One device, at `/arm`.
struct Cell1;
impl Component for Cell1 {
    fn declaration() -> Declaration {
        Declaration::new("cell")
            .uses::<Device>()
            .template(r#"<mujoco><worldbody><device name="arm"/></worldbody></mujoco>"#)
    }
}

struct Watch(Rc<Cell<bool>>);

impl Plugin for Watch {
    fn step(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        Ok(())
    }

    fn end(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        self.0.set(true);
        Ok(())
    }
}

/// Sends `signal` (a `kill` name) to this process while a platform runs: the run stops with
/// [`RuntimeError::Interrupted`] naming `number`, the plugins see the end, and the device gets
/// its stop.
fn a_signal_stops_the_run_cleanly(signal: &'static str, number: i32) {
    let ended = Rc::new(Cell::new(false));
    let server = Server::start(None);
    let error = Platform::builder()
        .world::<Cell1>()
        // Paced, so that ticks take real time and the signal has time to arrive.
        .environment("lab")
        .backend::<Lab>(|_, _| Ok(MockBackend::new(0.01, true)))
        .set(&format!("interfaces/arm/port={}", server.port()))
        .unwrap()
        .plugin(Watch(Rc::clone(&ended)))
        .behaviour(move |pl| async move {
            pl.wait_seconds(0.1).await?;
            let status = std::process::Command::new("kill")
                .args([&format!("-{signal}"), &std::process::id().to_string()])
                .status()?;
            assert!(status.success());
            pl.wait_forever().timeout(10.0).await?;
            Ok(())
        })
        .run()
        .unwrap_err();
    assert!(
        matches!(error, RuntimeError::Interrupted { signal } if signal == number),
        "{error}"
    );
    assert!(error.to_string().contains(signal), "{error}");
    assert!(ended.get());
    assert_eq!(server.received(1), ["STOP"], "the device was left safe");
}

/// One test for the three, in turn: a signal reaches every platform the process runs, so two
/// such tests as threads of one process (`cargo test`) would stop each other's runs.
#[test]
fn ctrl_c_sigterm_and_sighup_stop_the_run_plugins_see_the_end_and_devices_are_stopped() {
    for (signal, number) in [("INT", 2), ("TERM", 15), ("HUP", 1)] {
        a_signal_stops_the_run_cleanly(signal, number);
    }
}

/// Set in the child process of [`ctrl_c_ends_the_process_again_after_run`].
const CHILD: &str = "YAROK_CTRL_C_CHILD";

/// The child: runs a platform to its end, says so, then waits to be interrupted.
#[test]
fn ctrl_c_child() {
    if std::env::var_os(CHILD).is_none() {
        return;
    }
    Platform::builder()
        .world::<Empty>()
        .environment("mock")
        .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
        .behaviour(|pl| async move {
            pl.wait_seconds(0.05).await?;
            Ok(())
        })
        .run()
        .unwrap();
    println!("run ended");
    std::thread::sleep(std::time::Duration::from_secs(30));
    println!("still alive");
}

/// After `run()` returns, Ctrl-C ends the process, as it did before the run.
#[test]
fn ctrl_c_ends_the_process_again_after_run() {
    a_signal_ends_the_process_after_run("INT", 2);
}

/// After `run()` returns, SIGTERM ends the process, as it did before the run.
#[test]
fn sigterm_ends_the_process_again_after_run() {
    a_signal_ends_the_process_after_run("TERM", 15);
}

fn a_signal_ends_the_process_after_run(signal: &str, number: i32) {
    use std::io::{BufRead, BufReader};
    use std::os::unix::process::ExitStatusExt;
    let mut child = std::process::Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "ctrl_c_child", "--nocapture", "--test-threads=1"])
        .env(CHILD, "1")
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let ended = lines.find(|line| line.as_ref().is_ok_and(|l| l.contains("run ended")));
    assert!(ended.is_some(), "the child's run did not end");
    let status = std::process::Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let started = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > std::time::Duration::from_secs(10) {
            child.kill().unwrap();
            panic!("SIG{signal} was swallowed after run()");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    assert_eq!(status.signal(), Some(number), "{status:?}");
}
