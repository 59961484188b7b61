//! The Marlin driver against a third-party printer emulator: OctoPrint's VirtualPrinter (AGPL,
//! run as a separate process through `scripts/peers/virtual_printer_bridge.py` on a
//! pseudo-terminal; `scripts/setup-test-peers.sh` installs it). Homing, a square whose corners
//! `M114` reports within 0.01 mm after `M400`, and faults injected through its `!!DEBUG:`
//! channel and settings: a resend survived; a resend storm, a printer that stops answering, a
//! fatal error and a dropped connection each an error naming the printer, none a hang; a
//! printer unplugged mid-move and plugged back in reconnected, the move reported as failed and
//! the next one completing; an `ok` lost after `M400` found within seconds; a board that boots
//! for 3 s (deaf and silent, its banner late) connected with the default quiet time; the bridge
//! process is stopped whatever the test's outcome.

use std::time::Duration;

use yarok_hw::SerialPort;
use yarok_hw::marlin::{Marlin, MarlinError, MarlinSettings, Reconnecting};

use yarok_test::virtual_printer;

use virtual_printer::VirtualPrinter;

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

#[tokio::test]
async fn a_resend_storm_is_an_error_not_a_loop() {
    // Every line it receives comes back as a checksum error.
    let printer = VirtualPrinter::start(r#"{"sendWait": false, "resend_ratio": 100}"#);
    let mut marlin = printer.connect().await;
    let error = marlin.position().await.unwrap_err();
    assert!(
        matches!(&error, MarlinError::ResendStorm { command, .. } if command == "M114"),
        "{error}"
    );
}

#[tokio::test]
async fn unplugged_mid_move_and_back_the_move_fails_and_the_next_completes() {
    let printer = VirtualPrinter::replugging(r#"{"sendWait": false}"#, 0.5);
    let path = printer.path.clone();
    let open = async || SerialPort::open(&path, 250_000);
    let mut marlin = Reconnecting::connect(open, printer.settings())
        .await
        .unwrap();
    marlin.run(async |m| m.home().await).await.unwrap();
    let unplugged = marlin
        .run(async |m| {
            m.move_to([150.0, 150.0, 50.0], 20.0).await?;
            m.send_unnumbered("!!DEBUG:drop_connection").await?;
            m.finish_moves().await
        })
        .await
        .unwrap_err();
    assert!(
        matches!(&unplugged, MarlinError::Reconnected { cause, .. } if cause.is_connection_lost()),
        "{unplugged}"
    );
    assert!(unplugged.to_string().contains(&printer.path), "{unplugged}");
    assert!(printer.saw("dropped", Duration::ZERO) && printer.saw("replugged", Duration::ZERO));

    let corner = [40.0, 70.0, 5.0];
    let at = marlin
        .run(async |m| {
            m.home().await?;
            m.move_to(corner, 100.0).await?;
            m.finish_moves().await?;
            m.position().await
        })
        .await
        .unwrap();
    for (got, want) in [at.x, at.y, at.z].into_iter().zip(corner) {
        assert!((got - want).abs() <= 0.01, "{at:?} for {corner:?}");
    }
}

#[tokio::test]
async fn a_printer_that_does_not_come_back_is_an_error_in_time() {
    let printer = VirtualPrinter::start(r#"{"sendWait": false}"#);
    let path = printer.path.clone();
    let open = async || SerialPort::open(&path, 250_000);
    let mut settings = printer.settings();
    settings.replug_timeout = Duration::from_secs(1);
    let mut marlin = Reconnecting::connect(open, settings).await.unwrap();
    let started = std::time::Instant::now();
    let gone = marlin
        .run::<()>(async |m| {
            m.send_unnumbered("!!DEBUG:drop_connection").await?;
            loop {
                m.position().await?;
            }
        })
        .await
        .unwrap_err();
    assert!(matches!(gone, MarlinError::Unplugged { .. }), "{gone}");
    assert!(gone.to_string().contains(&printer.path), "{gone}");
    assert!(
        started.elapsed() < Duration::from_secs(5),
        "{:?}",
        started.elapsed()
    );
    let again = marlin.run(async |m| m.position().await).await.unwrap_err();
    assert!(matches!(again, MarlinError::Unplugged { .. }), "{again}");
}

/// OctoPrint's VirtualPrinter told not to answer the next line (`!!DEBUG:dont_answer`): the
/// `ok` of `M400` is lost. The printer, idle, keeps sending `wait`; the driver takes the second
/// as the sign, within a few of its `waitInterval`s, not after the 300 s motion limit.
#[tokio::test]
async fn a_lost_ok_after_m400_is_found_while_the_printer_waits() {
    let printer = VirtualPrinter::start(r#"{"sendWait": true, "waitInterval": 0.5}"#);
    let mut marlin = printer.connect().await;
    marlin.home().await.unwrap();
    marlin.send_unnumbered("!!DEBUG:dont_answer").await.unwrap();
    let started = std::time::Instant::now();
    let error = tokio::time::timeout(Duration::from_secs(20), marlin.finish_moves())
        .await
        .expect("the lost ok is found in time")
        .unwrap_err();
    assert!(matches!(error, MarlinError::LostAnswer { .. }), "{error}");
    assert!(
        started.elapsed() < Duration::from_secs(5),
        "{:?}",
        started.elapsed()
    );
    // The line is still good.
    marlin.finish_moves().await.unwrap();
}

/// A board that boots for 3 s after its port opens (a bootloader, a slow SD card): silent,
/// deaf to what it is sent, its start banner late. With the driver's default quiet time (1.5 s)
/// the handshake keeps trying within `boot_timeout` and the printer then moves.
#[tokio::test]
async fn a_board_that_boots_for_3_s_is_connected_with_the_default_quiet_time() {
    // The boot's 3 s count from when the bridge shows its device, within `start`.
    let started = std::time::Instant::now();
    let printer = VirtualPrinter::start(r#"{"bootSeconds": 3.0}"#);
    let port = SerialPort::open(&printer.path, 250_000).unwrap();
    let mut settings = MarlinSettings::new(printer.path.clone());
    settings.boot_timeout = Duration::from_secs(10);
    let mut marlin = Marlin::connect(port, settings).await.unwrap();
    assert!(started.elapsed() >= Duration::from_secs(3));
    let ignored = printer.ignored();
    assert!(
        ignored.iter().any(|line| line.contains("M110")),
        "the driver spoke while the board booted: {ignored:?}"
    );
    marlin.home().await.unwrap();
    marlin.move_to([10.0, 20.0, 5.0], 50.0).await.unwrap();
    marlin.finish_moves().await.unwrap();
    let at = marlin.position().await.unwrap();
    assert!(
        (at.x - 10.0).abs() < 0.01 && (at.y - 20.0).abs() < 0.01,
        "{at:?}"
    );
}
