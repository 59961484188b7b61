//! The `render` feature gates rendering: a world with no camera runs in `sim` without it, and a
//! camera or a tactile sensor in `sim` is refused before anything starts, naming the feature.
//! `scripts/test.sh` runs this file built with the default features and without them.

use yarok::components::worlds::{DigitWorld, PrinterWorld, TowerWorld};
#[cfg(not(feature = "render"))]
use yarok::components::{
    plugins::McapRecorder, plugins::McapRecorderSettings, worlds::PickAndPlaceWorld,
};
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

/// The model's own cameras are only rendered for recordings: asking for one is refused before
/// the run starts, naming the feature; with no camera asked for, the same world records.
#[cfg(not(feature = "render"))]
#[test]
fn recording_the_models_cameras_is_refused_naming_the_render_feature() {
    let folder = tempfile::tempdir().unwrap();
    let record = |cameras: Vec<String>| {
        let settings = McapRecorderSettings {
            path: folder.path().join("run.mcap"),
            cameras,
            ..McapRecorderSettings::default()
        };
        yarok::platform()
            .world::<PickAndPlaceWorld>()
            .plugin(McapRecorder::new(settings).unwrap())
            .behaviour(|pl| async move {
                pl.tick().await?;
                Ok(())
            })
            .run()
    };
    let error = record(vec!["overview".to_owned()]).unwrap_err();
    yarok_test::assert_says(
        &error,
        &[
            "plugin mcap",
            "the model's cameras needs rendering",
            "`render` feature",
        ],
    );
    record(Vec::new()).unwrap();
}

#[cfg(feature = "render")]
#[test]
fn with_the_render_feature_cameras_and_tactile_sensors_run_in_sim() {
    run_a_tick::<PrinterWorld>().unwrap();
    run_a_tick::<DigitWorld>().unwrap();
}
