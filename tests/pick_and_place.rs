//! The pick-and-place world: a block grasped by the 2F-85 stays in the gripper while the arm
//! carries it at `movel`'s full acceleration.

use std::f64::consts::PI;

use yarok::components::grippers::Robotiq2f85;
use yarok::components::robots::ur::{Ur5e, pose_from_vector};
use yarok::components::toys::{Block, Spot};
use yarok::components::worlds::PickAndPlaceWorld;
use yarok::nalgebra::{Point3, Vector3};

#[test]
fn a_grasped_block_does_not_slip_while_the_arm_accelerates() {
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
            let block: Block = pl.get("/medium")?;
            let table = pl.get::<Spot>("/target")?.position()[2];
            let down = |x: f64, y: f64, z: f64| pose_from_vector([x, y, z - table, PI, 0.0, 0.0]);
            let [x, y, _] = block.position();
            gripper.open().await?;
            arm.move_j_pose(down(x, y, table + 0.15)).await?;
            arm.move_l(down(x, y, table + 0.026)).await?;
            assert!(gripper.close().force(200).await?.object_detected);
            arm.move_l(down(x, y, table + 0.2)).await?;
            // The block in the TCP's frame, then while the arm accelerates at 1.2 m/s² along a
            // 40 cm line and stops.
            let held = || {
                let tcp = arm.tcp_pose();
                let at = Point3::from(block.position()) - Vector3::new(0.0, 0.0, table);
                tcp.inverse_transform_point(&at)
            };
            let start = held();
            let mut slip = 0.0f64;
            let carry = arm
                .move_l(down(x - 0.1, y + 0.38, table + 0.2))
                .acceleration(1.2);
            tokio::select! {
                biased;
                result = carry => result?,
                _ = pl.wait_forever().on_tick(|| slip = slip.max((held() - start).norm())) => {}
            }
            assert!(
                slip < 0.002,
                "the block slips {:.2} mm in the gripper",
                slip * 1000.0
            );
            assert!(gripper.object_detected());
            Ok(())
        })
        .run()
        .unwrap();
}
