//! The `printer_square` example with `--env real` against OctoPrint's VirtualPrinter: it homes
//! and traces the square, every corner reported within 0.01 mm; interrupted with Ctrl-C
//! mid-square it exits within seconds, saying it was interrupted, having sent the printer a
//! quick stop (`M410`) last and closed its port.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod support;
use support::example_binary;
use yarok_test::virtual_printer;

use example_binary::example_binary;
use virtual_printer::VirtualPrinter;

fn real(printer: &VirtualPrinter, laps: u32) -> Command {
    let mut command = Command::new(example_binary("printer_square"));
    command.args([
        "--env".to_owned(),
        "real".to_owned(),
        "--set".to_owned(),
        format!("interfaces/printer/port=\"{}\"", printer.path),
        "--set".to_owned(),
        "interfaces/printer/boot_seconds=1".to_owned(),
        "--set".to_owned(),
        format!("behaviour/laps={laps}"),
    ]);
    command
}

/// `t =   1.09 s: head at (150.00, 149.75, 10.00) mm` → [150.0, 149.75, 10.0].
fn head_at(line: &str) -> Option<[f64; 3]> {
    let inside = line.split_once("head at (")?.1.split_once(')')?.0;
    let values: Vec<f64> = inside.split(", ").filter_map(|v| v.parse().ok()).collect();
    values.try_into().ok()
}

#[test]
fn the_square_on_the_virtual_printer() {
    let printer = VirtualPrinter::start(r#"{"sendWait": false}"#);
    let output = real(&printer, 1).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    yarok_test::assert_succeeded(&output);
    let corners: Vec<[f64; 3]> = stdout.lines().filter_map(head_at).collect();
    let expected = [
        [100.0, 100.0],
        [150.0, 100.0],
        [150.0, 150.0],
        [100.0, 150.0],
        [100.0, 100.0],
    ];
    assert_eq!(corners.len(), expected.len(), "{stdout}");
    for (at, [x, y]) in corners.iter().zip(expected) {
        assert!(
            (at[0] - x).abs() <= 0.01 && (at[1] - y).abs() <= 0.01 && (at[2] - 10.0).abs() <= 0.01,
            "{at:?} for ({x}, {y})"
        );
    }
}

#[test]
fn ctrl_c_stops_the_printer_and_the_run() {
    let printer = VirtualPrinter::start(r#"{"sendWait": false}"#);
    let mut run = real(&printer, 1000)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(run.stdout.take().unwrap()).lines();
    let first = lines.next().expect("a corner").unwrap();
    assert!(head_at(&first).is_some(), "{first}");
    let status = Command::new("kill")
        .args(["-INT", &run.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let asked = Instant::now();
    let ended = loop {
        if let Some(status) = run.try_wait().unwrap() {
            break status;
        }
        assert!(
            asked.elapsed() < Duration::from_secs(10),
            "the run did not stop"
        );
        std::thread::sleep(Duration::from_millis(20));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut run.stderr.take().unwrap(), &mut stderr).unwrap();
    assert!(!ended.success(), "an interrupted run reports it");
    assert!(stderr.to_lowercase().contains("interrupt"), "{stderr}");
    assert!(
        printer.saw("closed", Duration::from_secs(2)),
        "the port was left open"
    );
    let received = printer.received();
    assert_eq!(
        received.last().map(String::as_str),
        Some("M410"),
        "the printer was not stopped last: {received:?}"
    );
}
