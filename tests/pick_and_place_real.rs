//! The `pick_and_place` example with `--env real` against the project's fake UR controller (a
//! simulated UR5e with a 2F-85 on its URCap socket, an object between the fingers at every grasp):
//! the same behaviour that stacks the blocks in `sim` completes every motion and grasp and exits 0.

use std::process::Command;

#[path = "support/example_binary.rs"]
mod example_binary;
#[path = "support/simulated_ur.rs"]
mod simulated_ur;
#[path = "../yarok-hw/tests/support/ur_controller/mod.rs"]
mod ur_controller;

use example_binary::example_binary;
use simulated_ur::SimulatedArm;
use ur_controller::{FakeController, Profile};

#[test]
fn pick_and_place_runs_on_the_fake_controller() {
    // The world's start pose; a block between the fingers whenever they close.
    let fake = FakeController::with_arm(
        Profile::ESeries,
        SimulatedArm::ur5e([0.0, -1.9, 1.9, -1.57, -1.57, 0.0]),
    );
    fake.place_object(Some(200));
    let host = format!("\"{}\"", fake.host);
    let output = Command::new(example_binary("pick_and_place"))
        .args(["--env", "real", "--set"])
        .arg(format!("interfaces/arm/host={host}"))
        .arg("--set")
        .arg(format!("interfaces/arm/gripper/host={host}"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert_eq!(stdout.matches("stacked").count(), 3 + 1, "{stdout}");
    assert!(
        stdout.contains("every motion and grasp completed"),
        "{stdout}"
    );
    let scripts = fake.scripts();
    let moves = scripts
        .iter()
        .filter(|s| s.trim().starts_with("movel("))
        .count();
    assert_eq!(moves, 3 * 6, "six lines a block: {scripts:?}");
    let grasps = fake.fingers().commands;
    assert!(
        grasps.iter().filter(|c| c.contains("POS 255")).count() >= 3,
        "{grasps:?}"
    );
}
