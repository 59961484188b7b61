//! The Robotiq 2F-85 in MuJoCo: its stroke follows the linkage's table, it detects a block it
//! closes on and nothing when it closes on air, speed requests set how fast it closes, and the
//! mock follows its requests.

use yarok::components::grippers::Robotiq2f85;
use yarok::components::worlds::EmptyWorld;
use yarok::prelude::*;

/// The gripper pointing down from a holder, over a 40 mm wide block (`block_half_width`).
struct GripperWorld;

impl Component for GripperWorld {
    fn declaration() -> Declaration {
        Declaration::new("gripper_world")
            .extends::<EmptyWorld>()
            .uses::<Robotiq2f85>()
            .default("block_half_width", 0.02)
            .template(
                r#"<mujoco><worldbody>
                  <body name="holder" pos="0 0 0.185" quat="0 1 0 0"><robotiq_2f85 name="gripper"/></body>
                  <body name="block" pos="0 0 0.03">
                    <freejoint/>
                    <geom type="box" size="0.015 {block_half_width} 0.03" mass="0.1" rgba="0.8 0.3 0.2 1"/>
                  </body>
                </worldbody></mujoco>"#,
            )
    }
}

#[test]
fn closing_on_a_block_detects_it_and_opening_releases_it() {
    yarok::platform()
        .world::<GripperWorld>()
        .behaviour(|pl| async move {
            let gripper: Robotiq2f85 = pl.get("/gripper")?;
            assert!(
                (gripper.opening_mm() - 85.4).abs() < 0.5,
                "{}",
                gripper.opening_mm()
            );
            let gripped = gripper.close().await?;
            assert!(gripped.object_detected, "{gripped:?}");
            // Stopped at the block's 40 mm: about 128 of 255 by the linkage's table.
            assert!(
                (gripper.opening_mm() - 40.0).abs() < 3.0,
                "{}",
                gripper.opening_mm()
            );
            let released = gripper.open().await?;
            assert!(
                !released.object_detected && released.position <= 3,
                "{released:?}"
            );
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn closing_on_nothing_reaches_the_request_and_detects_nothing() {
    yarok::platform()
        .world::<GripperWorld>()
        .set("block_half_width=0.005")
        .unwrap()
        .behaviour(|pl| async move {
            let gripper: Robotiq2f85 = pl.get("/gripper")?;
            // A 10 mm block stays clear of a 20 mm opening.
            let gripped = gripper.move_to_mm(20.0).await?;
            assert!(
                !gripped.object_detected,
                "{gripped:?} at {} mm",
                gripper.opening_mm()
            );
            assert!(
                (gripper.opening_mm() - 20.0).abs() < 1.5,
                "{}",
                gripper.opening_mm()
            );
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn the_speed_request_sets_how_fast_the_fingers_close() {
    let closing_time = |speed: u8| {
        let seconds = std::rc::Rc::new(std::cell::Cell::new(0.0));
        let out = std::rc::Rc::clone(&seconds);
        yarok::platform()
            .world::<GripperWorld>()
            .set("block_half_width=0.005")
            .unwrap()
            .behaviour(move |pl| async move {
                let gripper: Robotiq2f85 = pl.get("/gripper")?;
                let started = pl.time();
                gripper.move_to_mm(30.0).speed(speed).await?;
                out.set(pl.time() - started);
                Ok(())
            })
            .run()
            .unwrap();
        seconds.get()
    };
    let (fast, slow) = (closing_time(255), closing_time(0));
    // 55 mm at 150 and at 20 mm/s.
    assert!((fast - 55.0 / 150.0).abs() < 0.15, "fast: {fast} s");
    assert!((slow - 55.0 / 20.0).abs() < 0.3, "slow: {slow} s");
}

#[test]
fn a_mock_gripper_follows_its_requests() {
    yarok::platform()
        .world::<GripperWorld>()
        .environment("mock")
        .behaviour(|pl| async move {
            let gripper: Robotiq2f85 = pl.get("/gripper")?;
            let gripped = gripper.move_to(200).await?;
            assert_eq!(gripped.position, 200);
            assert!(!gripped.object_detected && !gripper.is_moving());
            Ok(())
        })
        .run()
        .unwrap();
}

/// Fingers that never come to rest (a gripper gone mute mid-grasp, as far as the request can
/// tell).
struct NeverStopping;

impl yarok::components::grippers::parallel::FingerDrive for NeverStopping {
    fn position(&self) -> f64 {
        0.0
    }

    fn is_moving(&self) -> bool {
        true
    }

    fn requested(&self) -> yarok::components::grippers::parallel::Request {
        yarok::components::grippers::parallel::Request::POWER_ON
    }

    fn request(&self, _: yarok::components::grippers::parallel::Request) {}
}

/// A gripper over [`NeverStopping`] fingers.
#[derive(Clone)]
struct StuckGripper(yarok::components::grippers::ParallelGripper);

impl Component for StuckGripper {
    fn declaration() -> Declaration {
        Declaration::new("stuck_gripper").template("<mujoco/>")
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Mock>();
    }
}

impl Interface<Mock> for StuckGripper {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        let stroke = yarok::components::grippers::Stroke::ROBOTIQ_2F85;
        let gripper = yarok::components::grippers::ParallelGripper::with_drive(
            bind,
            std::rc::Rc::new(NeverStopping),
            stroke,
        );
        Ok(Self(gripper))
    }
}

/// A grasp that does not finish in time is reported where the behaviour awaited it, not
/// inside yarok.
#[test]
fn a_grasp_that_times_out_is_reported_at_the_users_await() {
    let error = yarok::platform()
        .world::<StuckGripper>()
        .environment("mock")
        .behaviour(|pl| async move {
            let StuckGripper(gripper) = pl.get("/")?;
            gripper.close().await?;
            Ok(())
        })
        .run()
        .unwrap_err()
        .to_string();
    let awaited = format!("tests/robotiq_2f85.rs:{}:", line!() - 6);
    assert!(
        error.contains(&awaited) && error.contains("timed out"),
        "{error}"
    );
}
