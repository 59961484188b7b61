//! The Marlin driver against scripted printers, byte for byte: start-up, homing with
//! keep-alives, moves, the arrival barrier, positions in both firmwares' formats, resends,
//! errors, halts, restarts, silence, time limits, a closed line and a dropped command. Time is
//! tokio's paused clock, so the time limits pass instantly.

use std::time::Duration;

use tokio::io::DuplexStream;
use yarok_hw::marlin::{Marlin, MarlinError, MarlinSettings, Position};

use yarok_test::scripted_printer;

use scripted_printer::Step::{Bytes, Close, Expect, Send, Sleep};
use scripted_printer::{Step, printer, pseudo_terminal};

/// A driver connected to a printer playing `script` after its boot (`start`, an `echo:` line,
/// then quiet) and the `M110` handshake.
async fn connected(script: Vec<Step>) -> (Marlin<DuplexStream>, tokio::task::JoinHandle<()>) {
    let (ours, theirs) = tokio::io::duplex(4096);
    let mut whole = vec![
        Send(&[
            "start",
            "echo:Marlin 2.1.2",
            "echo: Last Updated: 2023-01-01",
        ]),
        Expect("N0 M110 N0*125"),
        Send(&["ok"]),
    ];
    whole.extend(script);
    let printer = tokio::spawn(printer(theirs, whole));
    let marlin = Marlin::connect(ours, MarlinSettings::new("/dev/ttyTEST"))
        .await
        .unwrap();
    (marlin, printer)
}

#[tokio::test(start_paused = true)]
async fn homing_with_keepalives_moves_and_the_arrival_barrier() {
    let (mut marlin, printer) = connected(vec![
        Expect("N1 G28*18"),
        Sleep(2.0),
        Send(&["echo:busy: processing"]),
        Sleep(2.0),
        Send(&[
            "echo:busy: processing",
            " T:21.30 /0.00 B:21.30 /0.00 @:0 B@:0",
        ]),
        Sleep(2.0),
        Send(&["ok"]),
        Expect("N2 G90*18"),
        Send(&["echo:Unknown command: \"G90\"", "ok"]),
        Expect("N3 G1 X10.000 Y20.000 Z5.000 F3000*29"),
        Send(&["ok N3 P15 B3"]),
        Expect("N4 M400*35"),
        Sleep(3.0),
        Send(&["wait", "ok"]),
        Expect("N5 M114*34"),
        Send(&[
            "X:10.00 Y:20.00 Z:5.00 E:0.00 Count X:800 Y:1600 Z:2000",
            "ok",
        ]),
        Expect("M410"),
        Send(&["ok"]),
    ])
    .await;
    marlin.home().await.unwrap();
    marlin.move_to([10.0, 20.0, 5.0], 50.0).await.unwrap();
    marlin.finish_moves().await.unwrap();
    let at = marlin.position().await.unwrap();
    assert_eq!(
        at,
        Position {
            x: 10.0,
            y: 20.0,
            z: 5.0
        }
    );
    marlin.quick_stop().await.unwrap();
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn the_virtual_printers_position_comes_on_its_ok_line() {
    let (mut marlin, printer) = connected(vec![
        Expect("N1 M114*38"),
        Send(&["ok X:10.0 Y:20.0 Z:5.0 E:0 Count: A:1000 B:2000 C:500"]),
        Expect("N2 M105*37"),
        Send(&["ok T:21.30/ 0.00 B:21.30/ 0.00 @:64"]),
    ])
    .await;
    assert_eq!(
        marlin.position().await.unwrap(),
        Position {
            x: 10.0,
            y: 20.0,
            z: 5.0
        }
    );
    let answer = marlin.command("M105").await.unwrap();
    assert_eq!(answer.position, None, "a temperature report is no position");
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn a_refused_line_is_sent_again_after_the_printer_acknowledges_it() {
    let (mut marlin, printer) = connected(vec![
        Expect("N1 G28*18"),
        // Stock Marlin's form, then the VirtualPrinter's.
        Send(&["Error:checksum mismatch, Last Line: 0", "Resend: 1", "ok"]),
        Expect("N1 G28*18"),
        Send(&["Error: expected line 1 got 2", "Resend:1", "ok"]),
        Expect("N1 G28*18"),
        Send(&["ok"]),
        Expect("N2 G90*18"),
        Send(&["ok"]),
    ])
    .await;
    marlin.home().await.unwrap();
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn absolute_coordinates_are_one_g90() {
    let (mut marlin, printer) = connected(vec![Expect("N1 G90*17"), Send(&["ok"])]).await;
    marlin.use_absolute_coordinates().await.unwrap();
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn a_resend_storm_is_an_error_naming_the_command() {
    let mut script = vec![Expect("N1 M114*38")];
    for _ in 0..9 {
        script.push(Send(&["Resend: 1", "ok"]));
        script.push(Expect("N1 M114*38"));
    }
    let (mut marlin, printer) = connected(script).await;
    let error = marlin.position().await.unwrap_err();
    assert!(
        matches!(&error, MarlinError::ResendStorm { command, resends: 9, .. } if command == "M114"),
        "{error}"
    );
    drop(marlin);
    printer.abort();
}

#[tokio::test(start_paused = true)]
async fn the_printers_errors_and_halts_reach_the_caller() {
    let (mut marlin, printer) = connected(vec![
        Expect("N1 G1 X1.000 Y2.000 Z3.000 F1200*25"),
        Send(&["!! Move out of range", "ok"]),
        Expect("N2 M400*37"),
        Send(&[
            "Error:Thermal Runaway, system stopped! Heater_ID: 0",
            "Error:Printer halted. kill() called!",
        ]),
    ])
    .await;
    let error = marlin.move_to([1.0, 2.0, 3.0], 20.0).await.unwrap_err();
    assert!(
        matches!(&error, MarlinError::Printer { message, .. } if message == "Move out of range"),
        "{error}"
    );
    assert!(error.to_string().contains("/dev/ttyTEST") && error.to_string().contains("G1 X1"));
    let error = marlin.finish_moves().await.unwrap_err();
    assert!(matches!(error, MarlinError::Halted { .. }), "{error}");
    // Halted: nothing more is sent.
    let error = marlin.position().await.unwrap_err();
    assert!(matches!(error, MarlinError::Halted { .. }), "{error}");
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn silence_time_limits_restarts_and_a_closed_line_are_errors_not_hangs() {
    // Silent: no answer at all.
    let (mut marlin, printer) = connected(vec![Expect("N1 M114*38")]).await;
    let started = tokio::time::Instant::now();
    let error = marlin.position().await.unwrap_err();
    assert!(matches!(error, MarlinError::Silent { .. }), "{error}");
    assert_eq!(started.elapsed(), Duration::from_secs(5));
    drop(marlin);
    printer.await.unwrap();

    // Busy forever: the command's time limit (10 s) ends it.
    let mut script = vec![Expect("N1 M114*38")];
    for _ in 0..10 {
        script.push(Sleep(2.0));
        script.push(Send(&["echo:busy: processing"]));
    }
    let (mut marlin, printer) = connected(script).await;
    let started = tokio::time::Instant::now();
    let error = marlin.position().await.unwrap_err();
    assert!(matches!(error, MarlinError::Timeout { .. }), "{error}");
    assert_eq!(started.elapsed(), Duration::from_secs(10));
    drop(marlin);
    printer.abort();

    // Restarted mid-command, and unplugged.
    let (mut marlin, printer) = connected(vec![
        Expect("N1 M400*38"),
        Send(&["start"]),
        Expect("N0 M110 N0*125"),
        Close,
    ])
    .await;
    let error = marlin.finish_moves().await.unwrap_err();
    assert!(matches!(error, MarlinError::Restarted { .. }), "{error}");
    let error = marlin.command("M110 N0").await.unwrap_err();
    assert!(matches!(error, MarlinError::Closed { .. }), "{error}");
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn a_dropped_commands_answer_is_read_before_the_next_command() {
    let (mut marlin, printer) = connected(vec![
        Expect("N1 M400*38"),
        Sleep(3.0),
        Send(&["ok"]),
        Expect("N2 M114*37"),
        Send(&["X:1.00 Y:2.00 Z:3.00 E:0.00 Count X:80 Y:160 Z:1200", "ok"]),
    ])
    .await;
    let cut = tokio::time::timeout(Duration::from_secs(1), marlin.finish_moves()).await;
    assert!(cut.is_err(), "M400 answered before its ok");
    assert_eq!(
        marlin.position().await.unwrap(),
        Position {
            x: 1.0,
            y: 2.0,
            z: 3.0
        }
    );
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn a_quick_stop_goes_out_at_once_though_a_move_is_awaited() {
    let (mut marlin, printer) = connected(vec![
        Expect("N1 G1 X10.000 Y20.000 Z5.000 F3000*31"),
        Send(&["ok"]),
        Expect("N2 M400*37"),
        // The move is long: M400 has no answer until M410 drops it.
        Expect("M410"),
        Send(&["ok", "ok"]),
        Expect("N3 M114*36"),
        Send(&["X:4.00 Y:5.00 Z:5.00 E:0.00 Count X:320 Y:400 Z:2000", "ok"]),
    ])
    .await;
    marlin.move_to([10.0, 20.0, 5.0], 50.0).await.unwrap();
    let cut = tokio::time::timeout(Duration::from_secs(1), marlin.finish_moves()).await;
    assert!(cut.is_err(), "M400 answered before its ok");
    marlin.quick_stop().await.unwrap();
    let at = marlin.position().await.unwrap();
    assert_eq!((at.x, at.y), (4.0, 5.0), "both oks were read before M114's");
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn commands_the_line_format_cannot_carry_are_refused_unsent() {
    let (mut marlin, printer) =
        connected(vec![Expect("N1 M114*38"), Send(&["ok X:0 Y:0 Z:0"])]).await;
    for bad in [
        "",
        "G1 X1*5",
        "M117 hi\nG28",
        "M117 ünïcode",
        "G1 X1 ; comment",
    ] {
        let error = marlin.command(bad).await.unwrap_err();
        assert!(
            matches!(error, MarlinError::InvalidCommand { .. }),
            "{bad:?}: {error}"
        );
    }
    let error = marlin
        .move_to([f64::NAN, 0.0, 0.0], 10.0)
        .await
        .unwrap_err();
    assert!(
        matches!(error, MarlinError::InvalidCommand { .. }),
        "{error}"
    );
    // The next good command is still line 1.
    marlin.position().await.unwrap();
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test(start_paused = true)]
async fn boot_noise_endless_lines_and_crlf_are_survived() {
    const LONG: &[u8] = &[b'#'; 5000];
    let (mut marlin, printer) = connected(vec![
        Expect("N1 M114*38"),
        Bytes(b"\x80\xff\xfe garbage\r\n"),
        Bytes(LONG),
        Bytes(b"\nX:1.50 Y:2.50 Z:3.50 E:0.00 Count X:1 Y:2 Z:3\r\nok\r\n"),
    ])
    .await;
    assert_eq!(
        marlin.position().await.unwrap(),
        Position {
            x: 1.5,
            y: 2.5,
            z: 3.5
        }
    );
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test]
async fn a_printer_on_a_pseudo_terminal_through_the_serial_port() {
    let (path, pty, printer_side) = pseudo_terminal();
    let printer = tokio::spawn(printer(
        printer_side,
        vec![
            Send(&["start"]),
            Expect("N0 M110 N0*125"),
            Send(&["ok"]),
            Expect("N1 M114*38"),
            Send(&["X:7.00 Y:8.00 Z:9.00 E:0.00 Count X:1 Y:2 Z:3", "ok"]),
        ],
    ));
    let port = yarok_hw::SerialPort::open(&path, 115_200).unwrap();
    drop(pty.slave);
    let mut settings = MarlinSettings::new(path.clone());
    settings.boot_quiet = Duration::from_millis(100);
    let mut marlin = Marlin::connect(port, settings).await.unwrap();
    assert_eq!(
        marlin.position().await.unwrap(),
        Position {
            x: 7.0,
            y: 8.0,
            z: 9.0
        }
    );
    drop(marlin);
    printer.await.unwrap();
}

#[tokio::test]
async fn serial_ports_that_cannot_be_used_are_errors_naming_them() {
    use yarok_hw::{SerialError, SerialPort};
    let error = SerialPort::open("/dev/ttyNOPE9", 115_200).unwrap_err();
    assert!(
        matches!(error, SerialError::Open { .. }) && error.to_string().contains("/dev/ttyNOPE9"),
        "{error}"
    );
    let error = SerialPort::open("/dev/null", 115_200).unwrap_err();
    assert!(
        matches!(error, SerialError::Setup { baud: 115_200, .. })
            && error.to_string().contains("/dev/null"),
        "{error}"
    );
}

/// The rate the kernel holds for the terminal, read by Python (an independent reader) through
/// the `TCGETS2` ioctl on the terminal given as its standard input.
fn kernel_baud_rate(terminal: std::os::fd::OwnedFd) -> u32 {
    const TERMIOS2: &str = "import fcntl, struct, sys\n\
        buf = fcntl.ioctl(0, 0x802C542A, bytes(44))\n\
        print(struct.unpack_from('I', buf, 40)[0])";
    let output = std::process::Command::new("python3")
        .args(["-c", TERMIOS2])
        .stdin(terminal)
        .output()
        .expect("python3 runs");
    assert!(output.status.success(), "{output:?}");
    String::from_utf8(output.stdout)
        .unwrap()
        .trim()
        .parse()
        .unwrap()
}

#[tokio::test]
async fn serial_ports_run_at_any_rate_the_device_takes() {
    use yarok_hw::SerialPort;
    for baud in [250_000, 500_000, 115_200, 74_880] {
        let (path, pty, _printer_side) = pseudo_terminal();
        let _port = SerialPort::open(&path, baud).unwrap();
        assert_eq!(kernel_baud_rate(pty.slave), baud, "{path}");
    }
}

/// A board silent past the quiet time (a bootloader, a slow SD card) that echoes the first
/// `M110` and starts 3 s after the port opened: `M110` is sent again, and after the late
/// banner once more, and acknowledged.
#[tokio::test(start_paused = true)]
async fn a_board_that_starts_late_after_echoing_m110_is_connected() {
    let (ours, theirs) = tokio::io::duplex(4096);
    let printer = tokio::spawn(printer(
        theirs,
        vec![
            // At 1.5 s of quiet the driver tries; the bootloader echoes it.
            Expect("N0 M110 N0*125"),
            Send(&["N0 M110 N0*125"]),
            // Unanswered for a second: sent again.
            Expect("N0 M110 N0*125"),
            Sleep(0.5),
            Send(&["start", "echo:Marlin 2.1.2"]),
            // After the banner and 1.5 s of quiet, once more.
            Expect("N0 M110 N0*125"),
            Send(&["ok"]),
            Expect("N1 M114*38"),
            Send(&["X:1.00 Y:2.00 Z:3.00 E:0.00 Count X:0 Y:0 Z:0", "ok"]),
        ],
    ));
    let started = tokio::time::Instant::now();
    let mut marlin = Marlin::connect(ours, MarlinSettings::new("/dev/ttyTEST"))
        .await
        .unwrap();
    assert_eq!(started.elapsed(), Duration::from_millis(4500));
    let position = marlin.position().await.unwrap();
    assert_eq!(
        position,
        Position {
            x: 1.0,
            y: 2.0,
            z: 3.0
        }
    );
    drop(marlin);
    printer.await.unwrap();
}

/// Garbage (as a wrong baud rate gives) and then nothing: `M110` is tried until the boot time
/// is up, and the error says so, naming what was heard.
#[tokio::test(start_paused = true)]
async fn garbage_then_silence_is_an_error_after_the_boot_time_naming_what_was_heard() {
    let (ours, theirs) = tokio::io::duplex(4096);
    let printer = tokio::spawn(printer(
        theirs,
        vec![Bytes(b"\xf0~\x8f\x1a~x\x80\n"), Sleep(100.0)],
    ));
    let started = tokio::time::Instant::now();
    let error = Marlin::connect(ours, MarlinSettings::new("/dev/ttyTEST"))
        .await
        .err()
        .unwrap();
    assert_eq!(started.elapsed(), Duration::from_secs(10));
    assert!(
        matches!(
            &error,
            MarlinError::NoHandshake {
                last_heard: Some(_),
                ..
            }
        ),
        "{error}"
    );
    let message = error.to_string();
    assert!(
        message.contains("baud rate") && message.contains("last heard"),
        "{message}"
    );
    printer.abort();
}

/// A boot time shorter than the quiet the driver waits for: `M110` still goes out when the boot
/// time is up, and is sent again until the silence limit has passed.
#[tokio::test(start_paused = true)]
async fn a_boot_time_shorter_than_the_quiet_still_gives_m110_its_window() {
    let (ours, theirs) = tokio::io::duplex(4096);
    let printer = tokio::spawn(printer(
        theirs,
        vec![
            Send(&["start", "SD card ok"]),
            Expect("N0 M110 N0*125"),
            Expect("N0 M110 N0*125"),
            Expect("N0 M110 N0*125"),
            Sleep(0.5),
            Send(&["ok"]),
        ],
    ));
    let mut settings = MarlinSettings::new("/dev/ttyTEST");
    settings.boot_timeout = Duration::from_secs(1);
    let started = tokio::time::Instant::now();
    Marlin::connect(ours, settings).await.unwrap();
    assert_eq!(started.elapsed(), Duration::from_millis(3500));
    printer.abort();
}

/// Garbage that never ends a line (a wrong baud rate at its worst), then nothing: the error
/// quotes the bytes heard rather than saying the printer sent nothing.
#[tokio::test(start_paused = true)]
async fn garbage_without_a_line_end_is_quoted_not_called_nothing() {
    let (ours, theirs) = tokio::io::duplex(4096);
    let printer = tokio::spawn(printer(
        theirs,
        vec![Bytes(b"\xf0~\x8f\x1a~x\x80"), Sleep(100.0)],
    ));
    let error = Marlin::connect(ours, MarlinSettings::new("/dev/ttyTEST"))
        .await
        .err()
        .unwrap();
    let message = error.to_string();
    let heard = format!("{:?}", "\u{fffd}~\u{fffd}\u{1a}~x\u{fffd}");
    assert!(
        message.contains(&format!("last heard: {heard}")) && !message.contains("sent nothing"),
        "{message}"
    );
    printer.abort();
}
