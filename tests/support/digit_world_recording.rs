//! `yarok run digit_world --record FILE` with a `joints_csv` file beside the recording, which
//! what others' tools read back from the recording is checked against.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::joints_csv::JointsCsv;

/// Runs `yarok run digit_world --record {folder}/run.mcap` with `options` and a `joints_csv`
/// row every 10 ticks; the recording and the CSV, once the run succeeded.
pub(crate) fn record_digit_world(folder: &Path, options: &[&str]) -> (PathBuf, JointsCsv) {
    let mcap = folder.join("run.mcap");
    let csv = folder.join("joints.csv");
    let output = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .current_dir(folder)
        .args(["run", "digit_world", "--record"])
        .arg(&mcap)
        .args(options)
        .arg("--set")
        .arg(format!(
            "plugins/joints_csv/path={:?}",
            csv.display().to_string()
        ))
        .args(["--set", "plugins/joints_csv/every=10"])
        .output()
        .unwrap();
    yarok_test::assert_succeeded(&output);
    (mcap, JointsCsv::read(&csv))
}

/// Asserts what a DIGIT's depth frames (`(nearest, farthest)` metres each) must show in a
/// `digit_world` recording: the gel's face is 18 mm from the camera, 2 mm thick, and the grasp
/// presses it in.
pub(crate) fn assert_gel_depths(depths: &[(f64, f64)], what: &str) {
    assert!(!depths.is_empty(), "{what}: no depth frames");
    assert!(
        depths
            .iter()
            .all(|(near, far)| *near > 0.015 && *far <= 0.0181),
        "{what}: {depths:?}"
    );
    assert!(
        depths.iter().any(|(near, _)| *near < 0.0175),
        "{what}: the grasp shows in the depth"
    );
}
