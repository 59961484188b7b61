//! One device, four environments, each in its own file: a linear slide (`slide/`) written as a
//! bundled device is — a handle over a drive, the drive implemented once per environment — runs
//! the same behaviour in `sim` (MuJoCo), `mock`, `real` (a Marlin board's X axis: OctoPrint's
//! VirtualPrinter on a pseudo-terminal) and `replay`, a user's own environment added in
//! `slide/replay.rs` without touching the handle.

mod slide;

use std::cell::RefCell;
use std::rc::Rc;

use yarok::core::component::MockBackend;
use yarok::prelude::*;
use yarok_test::virtual_printer::VirtualPrinter;

use slide::{Replay, Slide};

/// A bench with one slide on it.
struct Bench;

impl Component for Bench {
    fn declaration() -> Declaration {
        Declaration::new("bench")
            .uses::<Slide>()
            .template(r#"<mujoco><worldbody><slide name="slide"/></worldbody></mujoco>"#)
    }
}

/// The behaviour: the carriage to 50 mm, then back to 20 mm. What it saw: the platform time
/// of each arrival and where the carriage then was.
fn out_and_back(arguments: &[String]) -> Vec<(f64, f64)> {
    let seen = Rc::new(RefCell::new(Vec::new()));
    let kept = Rc::clone(&seen);
    yarok::platform()
        .world::<Bench>()
        .backend::<Replay>(|_, _| Ok(MockBackend::new(0.002, false)))
        .args(arguments.iter().cloned())
        .unwrap()
        .behaviour(move |pl| async move {
            let slide: Slide = pl.get("/slide")?;
            for target in [50.0, 20.0] {
                slide.move_to(target).await?;
                kept.borrow_mut().push((pl.time(), slide.at()));
            }
            Ok(())
        })
        .run()
        .unwrap();
    seen.take()
}

fn in_environment(environment: &str) -> Vec<(f64, f64)> {
    out_and_back(&["--env".to_owned(), environment.to_owned()])
}

fn assert_arrived(seen: &[(f64, f64)]) {
    assert_eq!(seen.len(), 2, "{seen:?}");
    for ((_, at), target) in seen.iter().zip([50.0, 20.0]) {
        assert!((at - target).abs() < 0.1, "{seen:?}");
    }
}

#[test]
fn in_sim_the_servo_carries_the_carriage_there_in_time() {
    let seen = in_environment("sim");
    assert_arrived(&seen);
    // A 0.5 kg carriage on a 400 N/m servo, damped near critically, settles in a fraction
    // of a second: not at once, and not never.
    let (out, back) = (seen[0].0, seen[1].0 - seen[0].0);
    assert!(
        (0.05..2.0).contains(&out) && (0.05..2.0).contains(&back),
        "{seen:?}"
    );
}

#[test]
fn in_mock_the_carriage_is_there_at_the_next_tick() {
    let seen = in_environment("mock");
    assert_arrived(&seen);
    assert!(seen[1].0 - seen[0].0 <= 0.002 + 1e-9, "{seen:?}");
}

#[test]
fn in_replay_the_carriage_is_where_the_recording_says() {
    let seen = in_environment("replay");
    assert_arrived(&seen);
    // The recording reaches 50 mm at 1.0 s and 20 mm at 2.0 s.
    assert!((seen[0].0 - 1.0).abs() < 0.011, "{seen:?}");
    assert!((seen[1].0 - 2.0).abs() < 0.011, "{seen:?}");
}

#[test]
fn in_real_a_marlin_board_moves_the_carriage() {
    let printer = VirtualPrinter::start(r#"{"sendWait": false}"#);
    let seen = out_and_back(&[
        "--env".to_owned(),
        "real".to_owned(),
        "--set".to_owned(),
        format!("interfaces/slide/port=\"{}\"", printer.path),
    ]);
    assert_arrived(&seen);
    let received = printer.received();
    let sent = |x: &str| {
        received
            .iter()
            .any(|line| line.contains(&format!(" G1 X{x} ")))
    };
    assert!(sent("50.000") && sent("20.000"), "{received:?}");
    assert!(
        received.iter().any(|line| line.contains("M410")),
        "{received:?}"
    );
}
