//! The Robotiq 2F-85 with `--env real`: the same behaviour as in `sim` drives the gripper
//! through the URCap socket of the project's fake UR controller — activated at bind, a close
//! that stops on an object (`object_detected`), an open to the position — and a gripper fault
//! ends the run with an error naming the component and the fault.

use std::time::Duration;

use yarok::components::grippers::Robotiq2f85;
use yarok::{Component, Declaration};

use yarok_test::ur_controller;

use ur_controller::{FakeController, Profile};
use yarok_test::assert_says;

/// Just the gripper.
struct GripperOnly;

impl Component for GripperOnly {
    fn declaration() -> Declaration {
        Declaration::new("gripper_only")
            .uses::<Robotiq2f85>()
            .template(r#"<mujoco><worldbody><robotiq_2f85 name="gripper"/></worldbody></mujoco>"#)
    }
}

fn real(fake: &FakeController) -> yarok::core::runtime::PlatformBuilder {
    yarok::platform()
        .world::<GripperOnly>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/gripper/host=\"{}\"", fake.host),
        ])
        .unwrap()
}

async fn grasp(pl: yarok::Pl) -> yarok::BehaviourResult {
    let gripper: Robotiq2f85 = pl.get("/gripper")?;
    let closed = gripper.close().speed(255).force(100).await?;
    assert!(closed.object_detected, "{closed:?}");
    assert_eq!(closed.position, 120);
    let opened = gripper.open().await?;
    assert!(!opened.object_detected, "{opened:?}");
    assert_eq!(opened.position, 0);
    Ok(())
}

#[test]
fn the_same_behaviour_grasps_with_the_real_gripper() {
    let fake = FakeController::start(Profile::ESeries);
    fake.place_object(Some(120));
    real(&fake).behaviour(grasp).run().unwrap();
    let fingers = fake.fingers();
    assert_eq!(fingers.sta, 3, "activated at bind");
    assert!(
        fingers
            .commands
            .iter()
            .any(|c| c == "SET POS 255 SPE 255 FOR 100 GTO 1"),
        "{:?}",
        fingers.commands
    );
}

#[test]
fn a_gripper_fault_ends_the_run_naming_it() {
    let fake = FakeController::start(Profile::Cb3);
    let faulting = std::thread::scope(|scope| {
        scope.spawn(|| {
            std::thread::sleep(Duration::from_millis(400));
            fake.gripper_fault(14);
        });
        real(&fake)
            .behaviour(|pl| async move {
                let gripper: Robotiq2f85 = pl.get("/gripper")?;
                gripper.close().speed(0).await?;
                Ok(())
            })
            .run()
    });
    let error = faulting.unwrap_err().to_string();
    assert_says(&error, &["/gripper", "overcurrent"]);
}
