//! The quarter turn, tick by tick, in `sim` and in `mock`: the same behaviour, two drives.

use std::cell::Cell;
use std::rc::Rc;

use my_turntable::{Showroom, quarter_turn};

/// Runs the quarter turn in `environment`; the angle reached and the platform time it took.
fn turn(environment: &str) -> (f64, f64) {
    let reached = Rc::new(Cell::new(f64::NAN));
    let seen = Rc::clone(&reached);
    let mut platform = yarok::platform()
        .world::<Showroom>()
        .args(["--env".to_owned(), environment.to_owned()])
        .unwrap()
        .behaviour(move |pl| async move {
            seen.set(quarter_turn(pl).await?);
            Ok(())
        })
        .build()
        .unwrap();
    while platform.step().unwrap() {}
    (reached.get(), platform.pl().time())
}

#[test]
fn the_turntable_turns_a_quarter_in_sim_and_in_mock() {
    let (angle, took) = turn("sim");
    assert!(
        (angle - std::f64::consts::FRAC_PI_2).abs() < 0.01,
        "{angle}"
    );
    // A servo turning a disc takes time; a mock is there at once.
    assert!(took > 0.1, "{took}");
    let (angle, took) = turn("mock");
    assert_eq!(angle, std::f64::consts::FRAC_PI_2);
    assert!(took < 0.01, "{took}");
}

#[test]
fn reruns_are_bit_identical() {
    assert_eq!(turn("sim").0.to_bits(), turn("sim").0.to_bits());
}
