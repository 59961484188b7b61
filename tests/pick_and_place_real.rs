//! The `pick_and_place` example with `--env real` against the project's fake UR controller (a
//! simulated UR5e with a 2F-85 on its URCap socket, an object between the fingers at every grasp):
//! the same behaviour that stacks the blocks in `sim` completes every motion and grasp and exits 0;
//! when every connection to the controller drops at once (a network blip), arm and gripper are
//! reconnected and the behaviour carries on; a typo in the arm's settings is reported before the
//! gripper (bound first, as the arm's child) is touched.

use std::process::Command;
use std::sync::Arc;
use std::time::{Duration, Instant};

use yarok::components::grippers::Robotiq2f85;
use yarok::components::robots::ur::Ur5e;
use yarok::components::worlds::PickAndPlaceWorld;

mod support;
use support::example_binary;
use support::simulated_ur;
use yarok_test::ur_controller;

use example_binary::example_binary;
use simulated_ur::SimulatedArm;
use ur_controller::{FakeController, Profile};
use yarok_test::assert_says;

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
    yarok_test::assert_succeeded(&output);
    assert_eq!(stdout.matches("stacked").count(), 3 + 1, "{stdout}");
    assert_says(&stdout, &["every motion and grasp completed"]);
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

/// A network blip drops RTDE, the secondary interface and the gripper's socket together, while
/// the arm moves: both are reconnected, the motion arrives, and the gripper grasps; the time
/// from the drop until both have answered again is printed.
#[test]
fn arm_and_gripper_come_back_after_every_connection_drops() {
    let start = [0.0, -1.9, 1.9, -1.57, -1.57, 0.0];
    let fake = Arc::new(FakeController::with_arm(
        Profile::ESeries,
        SimulatedArm::ur5e(start),
    ));
    fake.place_object(Some(200));
    let host = format!("\"{}\"", fake.host);
    let dropping = Arc::clone(&fake);
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/arm/host={host}"),
            "--set".to_owned(),
            format!("interfaces/arm/gripper/host={host}"),
        ])
        .unwrap()
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
            let connections = dropping.rtde_connections();
            let target = [0.4, -1.8, 1.8, -1.57, -1.57, 0.0];
            let moving = arm.move_j(target).speed(1.0);
            let dropped = Instant::now();
            dropping.drop_streams();
            let (moved, grasp) = tokio::join!(moving, gripper.close().speed(255));
            let back = dropped.elapsed();
            moved?;
            assert!(arm.is_at(&target), "{:?}", arm.q());
            assert!(grasp?.object_detected);
            assert!(
                dropping.rtde_connections() > connections,
                "RTDE was not reconnected"
            );
            // What the same motions take with every connection up.
            let undisturbed = Instant::now();
            let (moved, opened) =
                tokio::join!(arm.move_j(start).speed(1.0), gripper.open().speed(255));
            moved?;
            opened?;
            println!(
                "after the drop, arm moved and gripper grasped in {back:?}; undisturbed {:?}",
                undisturbed.elapsed()
            );
            assert!(back < undisturbed.elapsed() + Duration::from_secs(2));
            Ok(())
        })
        .run()
        .unwrap();
    assert!(
        fake.fingers()
            .commands
            .iter()
            .filter(|c| c.contains("POS 255"))
            .count()
            == 1,
        "the close was sent once, or again only because it was lost: {:?}",
        fake.fingers().commands
    );
}

#[test]
fn a_typo_in_the_arms_settings_is_reported_before_the_gripper_is_touched() {
    let fake = FakeController::start(Profile::ESeries);
    let host = format!("\"{}\"", fake.host);
    let error = yarok::platform()
        .world::<PickAndPlaceWorld>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/arm/hots={host}"),
            "--set".to_owned(),
            format!("interfaces/arm/gripper/host={host}"),
        ])
        .unwrap()
        .run()
        .unwrap_err()
        .to_string();
    assert_says(&error, &["/arm", "hots", "host"]);
    let fingers = fake.fingers();
    assert!(
        fingers.commands.is_empty() && fingers.sta == 0,
        "the gripper was activated: {:?}",
        fingers.commands
    );
}
