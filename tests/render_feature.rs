//! The `render` feature gates rendering: a world with no camera runs in `sim` without it, and a
//! camera or a tactile sensor in `sim` is refused before anything starts, naming the feature.
//! `scripts/test.sh` runs this file built with the default features and without them.

use yarok::components::worlds::{DigitWorld, PrinterWorld, TowerWorld};
use yarok::core::runtime::RuntimeError;

#[test]
fn a_world_without_cameras_runs_in_sim() {
    yarok::platform()
        .world::<TowerWorld>()
        .behaviour(|pl| async move {
            pl.wait_seconds(0.1).await?;
            assert!(pl.ticks() >= 50, "{} ticks", pl.ticks());
            Ok(())
        })
        .run()
        .unwrap();
}

/// Runs `World` in `sim` for a tick.
fn run_a_tick<W: yarok::Component>() -> Result<(), RuntimeError> {
    yarok::platform()
        .world::<W>()
        .behaviour(|pl| async move {
            pl.tick().await?;
            Ok(())
        })
        .run()
}

#[cfg(not(feature = "render"))]
#[test]
fn cameras_and_tactile_sensors_in_sim_are_refused_naming_the_render_feature() {
    let error = run_a_tick::<PrinterWorld>().unwrap_err();
    assert!(matches!(error, RuntimeError::Unsupported { .. }), "{error}");
    yarok_test::assert_says(
        &error,
        &[
            "/printer/cam (Cam) supports mock",
            "build yarok with the `render` feature",
        ],
    );
    let error = run_a_tick::<DigitWorld>().unwrap_err();
    yarok_test::assert_says(
        &error,
        &[
            "/arm/gripper/left_digit (Digit) supports mock",
            "the `render` feature",
        ],
    );
}

#[cfg(feature = "render")]
#[test]
fn with_the_render_feature_cameras_and_tactile_sensors_run_in_sim() {
    run_a_tick::<PrinterWorld>().unwrap();
    run_a_tick::<DigitWorld>().unwrap();
}
