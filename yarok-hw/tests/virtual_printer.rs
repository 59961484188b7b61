//! The Marlin driver against a third-party printer emulator: OctoPrint's VirtualPrinter (AGPL,
//! run as a separate process through `scripts/peers/virtual_printer_bridge.py` on a
//! pseudo-terminal; `scripts/setup-test-peers.sh` installs it). Homing, a square whose corners
//! `M114` reports within 0.01 mm after `M400`, and faults injected through its `!!DEBUG:`
//! channel: a resend, a printer that stops answering, a fatal error, a dropped connection —
//! each an error naming the printer, none a hang; no process or port is left open.

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use yarok_hw::SerialPort;
use yarok_hw::marlin::{Marlin, MarlinError, MarlinSettings};

/// The VirtualPrinter behind a pseudo-terminal, stopped when dropped.
struct VirtualPrinter {
    bridge: Child,
    path: String,
}

impl VirtualPrinter {
    /// Starts one with these settings (JSON) over the plugin's defaults.
    fn start(settings: &str) -> Self {
        let peers = std::env::var_os("YAROK_CACHE_DIR")
            .map(PathBuf::from)
            .or_else(|| {
                std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cache/yarok"))
            })
            .expect("YAROK_CACHE_DIR or HOME")
            .join("peers/bin/python");
        assert!(
            peers.exists(),
            "{} is missing: run `bash scripts/setup-test-peers.sh` (scripts/test.sh does)",
            peers.display()
        );
        let bridge = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../scripts/peers/virtual_printer_bridge.py"
        );
        let mut bridge = Command::new(peers)
            .arg(bridge)
            .arg(settings)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("the bridge starts");
        let mut path = String::new();
        BufReader::new(bridge.stdout.take().expect("its output"))
            .read_line(&mut path)
            .expect("the bridge names its device");
        Self {
            bridge,
            path: path.trim().to_owned(),
        }
    }

    async fn connect(&self) -> Marlin<SerialPort> {
        let mut settings = MarlinSettings::new(self.path.clone());
        settings.boot_quiet = Duration::from_millis(300);
        settings.silence = Duration::from_secs(2);
        let port = SerialPort::open(&self.path, 115_200).expect("the device opens");
        Marlin::connect(port, settings)
            .await
            .expect("the printer answers")
    }
}

impl Drop for VirtualPrinter {
    fn drop(&mut self) {
        let _ = self.bridge.kill();
        let _ = self.bridge.wait();
    }
}

#[tokio::test]
async fn homing_and_a_square_whose_corners_m114_confirms() {
    let printer = VirtualPrinter::start(r#"{"sendWait": false}"#);
    let mut marlin = printer.connect().await;
    marlin.home().await.unwrap();
    for corner in [
        [10.0, 10.0, 5.0],
        [60.0, 10.0, 5.0],
        [60.0, 60.0, 5.0],
        [10.0, 60.0, 5.0],
    ] {
        marlin.move_to(corner, 100.0).await.unwrap();
        marlin.finish_moves().await.unwrap();
        let at = marlin.position().await.unwrap();
        for (axis, (got, want)) in [at.x, at.y, at.z].iter().zip(corner).enumerate() {
            assert!((got - want).abs() <= 0.01, "axis {axis}: {got} for {want}");
        }
    }
    marlin.quick_stop().await.unwrap();
}

#[tokio::test]
async fn a_resend_is_survived_and_a_silent_printer_is_an_error() {
    let printer = VirtualPrinter::start(r#"{"sendWait": false}"#);
    let mut marlin = printer.connect().await;
    marlin
        .send_unnumbered("!!DEBUG:trigger_resend_checksum")
        .await
        .unwrap();
    marlin.move_to([20.0, 30.0, 5.0], 100.0).await.unwrap();
    marlin.finish_moves().await.unwrap();
    let at = marlin.position().await.unwrap();
    assert!(
        (at.x - 20.0).abs() <= 0.01 && (at.y - 30.0).abs() <= 0.01,
        "{at:?}"
    );

    marlin.send_unnumbered("!!DEBUG:dont_answer").await.unwrap();
    let error = marlin.position().await.unwrap_err();
    assert!(matches!(error, MarlinError::Silent { .. }), "{error}");
    assert!(error.to_string().contains(&printer.path), "{error}");
}

#[tokio::test]
async fn a_fatal_error_and_a_dropped_connection_end_in_errors_not_hangs() {
    let printer = VirtualPrinter::start(r#"{"sendWait": false}"#);
    let mut marlin = printer.connect().await;
    marlin
        .send_unnumbered("!!DEBUG:trigger_fatal_error_marlin")
        .await
        .unwrap();
    let error = marlin.position().await.unwrap_err();
    assert!(matches!(error, MarlinError::Halted { .. }), "{error}");

    let printer = VirtualPrinter::start(r#"{"sendWait": false}"#);
    let mut marlin = printer.connect().await;
    marlin
        .send_unnumbered("!!DEBUG:drop_connection")
        .await
        .unwrap();
    // The printer drops the line once it has read the request: a few commands later at most.
    let mut answered = 0;
    let error = loop {
        match marlin.position().await {
            Ok(_) if answered < 20 => answered += 1,
            Ok(_) => panic!("the connection was never dropped"),
            Err(error) => break error,
        }
    };
    assert!(
        matches!(
            error,
            MarlinError::Closed { .. } | MarlinError::Silent { .. } | MarlinError::Io { .. }
        ),
        "{error}"
    );
    assert!(error.to_string().contains(&printer.path), "{error}");
}
