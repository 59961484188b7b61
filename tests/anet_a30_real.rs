//! The Anet A30 with `--env real`: the same behaviour as in `sim` drives a (scripted) Marlin
//! printer on a pseudo-terminal — homing at start, the move sent with the configured feed, the
//! arrival awaited (`M400`) and read back (`M114`), a quick stop (`M410`) at shutdown; a port
//! that does not exist is an error naming the component and the port; OctoPrint's
//! VirtualPrinter unplugged mid-move and plugged back in is homed again and the behaviour's move
//! completes.

use yarok::components::robots::AnetA30;
use yarok::{Component, Declaration};

use yarok_test::scripted_printer;
use yarok_test::virtual_printer;

use scripted_printer::Step::{Expect, Send, Sleep};
use scripted_printer::{printer, pseudo_terminal};
use yarok_test::assert_says;

/// Just the printer.
struct PrinterOnly;

impl Component for PrinterOnly {
    fn declaration() -> Declaration {
        Declaration::new("printer_only")
            .uses::<AnetA30>()
            .template(r#"<mujoco><worldbody><anet_a30 name="printer"/></worldbody></mujoco>"#)
    }
}

async fn square_corner(pl: yarok::Pl) -> yarok::BehaviourResult {
    let printer: AnetA30 = pl.get("/printer")?;
    let target = printer.move_to([10.0, 20.0, 5.0]);
    pl.wait(|| printer.is_at(target)).timeout(5.0).await?;
    assert_eq!(printer.at(), [10.0, 20.0, 5.0]);
    Ok(())
}

#[test]
fn the_same_behaviour_drives_a_real_printer() {
    let script = vec![
        Send(&["start", "echo:Marlin 2.1.2"]),
        Expect("N0 M110 N0*125"),
        Send(&["ok"]),
        Expect("N1 G28*18"),
        Send(&["echo:busy: processing", "ok"]),
        Expect("N2 G90*18"),
        Send(&["ok"]),
        Expect("N3 M114*36"),
        Send(&["X:0.00 Y:0.00 Z:0.00 E:0.00 Count X:0 Y:0 Z:0", "ok"]),
        Expect("N4 G1 X10.000 Y20.000 Z5.000 F3000*26"),
        Send(&["ok"]),
        Expect("N5 M400*34"),
        Sleep(0.3),
        Send(&["ok"]),
        Expect("N6 M114*33"),
        Send(&[
            "X:10.00 Y:20.00 Z:5.00 E:0.00 Count X:800 Y:1600 Z:2000",
            "ok",
        ]),
        Expect("M410"),
        Send(&["ok"]),
    ];
    let (path_tx, path_rx) = std::sync::mpsc::channel();
    // The printer plays on a thread of its own, as a real one would.
    let printer_thread = std::thread::spawn(move || {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .unwrap();
        runtime.block_on(async {
            let (path, pty, printer_side) = pseudo_terminal();
            // The device side goes to the test, which closes it once the run is over.
            path_tx.send((path, pty.slave)).unwrap();
            printer(printer_side, script).await;
        });
    });
    let (path, device_side) = path_rx.recv().unwrap();
    yarok::platform()
        .world::<PrinterOnly>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/printer/port=\"{path}\""),
        ])
        .unwrap()
        .behaviour(square_corner)
        .run()
        .unwrap();
    drop(device_side);
    printer_thread.join().unwrap();
}

#[test]
fn a_missing_port_is_an_error_naming_the_component_and_the_port() {
    let error = yarok::platform()
        .world::<PrinterOnly>()
        .args(
            [
                "--env",
                "real",
                "--set",
                "interfaces/printer/port=\"/dev/ttyNOPE7\"",
            ]
            .map(str::to_owned),
        )
        .unwrap()
        .behaviour(square_corner)
        .run()
        .unwrap_err()
        .to_string();
    assert_says(&error, &["/printer", "/dev/ttyNOPE7"]);
}

async fn far_corner(pl: yarok::Pl) -> yarok::BehaviourResult {
    let printer: AnetA30 = pl.get("/printer")?;
    let target = printer.move_to([120.0, 130.0, 20.0]);
    pl.wait(|| printer.is_at(target)).timeout(60.0).await?;
    Ok(())
}

#[test]
fn a_printer_unplugged_mid_move_and_back_is_homed_and_the_move_completes() {
    let printer = virtual_printer::VirtualPrinter::replugging(r#"{"sendWait": false}"#, 0.5);
    std::thread::scope(|scope| {
        scope.spawn(|| {
            // Mid-move: the move (about 1.5 s on this printer) was sent a moment ago.
            let sent = |line: &String| line.contains(" G1 X120.000");
            // Bounded: a run that failed before the move must not hang the test.
            let waiting = std::time::Instant::now();
            while !printer.received().iter().any(sent) {
                if waiting.elapsed() > std::time::Duration::from_secs(60) {
                    return;
                }
                std::thread::sleep(std::time::Duration::from_millis(20));
            }
            std::thread::sleep(std::time::Duration::from_millis(300));
            printer.inject("!!DEBUG:drop_connection");
        });
        yarok::platform()
            .world::<PrinterOnly>()
            .args([
                "--env".to_owned(),
                "real".to_owned(),
                "--set".to_owned(),
                format!("interfaces/printer/port=\"{}\"", printer.path),
                "--set".to_owned(),
                "interfaces/printer/boot_seconds=1".to_owned(),
                "--set".to_owned(),
                "interfaces/printer/feed=15".to_owned(),
            ])
            .unwrap()
            .behaviour(far_corner)
            .run()
            .unwrap();
    });
    assert!(printer.saw("replugged", std::time::Duration::ZERO));
    let received = printer.received();
    let homed = received.iter().filter(|line| line.contains(" G28")).count();
    assert_eq!(
        homed, 2,
        "homed at start and after coming back: {received:?}"
    );
}
