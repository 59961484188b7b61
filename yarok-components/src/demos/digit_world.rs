//! The DigitWorld demo: what the DIGITs feel of a grasped block.

use std::f64::consts::PI;

use yarok_core::runtime::{BehaviourResult, Pl};

use super::out_folder;
use crate::grippers::Robotiq2f85;
use crate::robots::ur::{Ur5e, pose_from_vector};
use crate::tactile_sensors::Digit;
use crate::toys::{Block, Spot};

/// In a [`DigitWorld`](crate::worlds::DigitWorld): picks the medium block and puts it on the
/// target; once the block is grasped, saves what each DIGIT sees (`OUT/digit_left.png`,
/// `OUT/digit_right.png`, OUT the behaviour's setting `out`, default `out`). Fails if a sensor
/// feels nothing while the block is held.
pub async fn feel(pl: Pl) -> BehaviourResult {
    let arm: Ur5e = pl.get("/arm")?;
    let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
    let digits: [Digit; 2] = [
        pl.get("/arm/gripper/left_digit")?,
        pl.get("/arm/gripper/right_digit")?,
    ];
    let (block, target): (Block, Spot) = (pl.get("/medium")?, pl.get("/target")?);
    let out = out_folder(&pl)?;
    // The TCP pointing down, `z` above the table, in the arm's base frame.
    let down = |[x, y, _]: [f64; 3], z: f64| pose_from_vector([x, y, z, PI, 0.0, 0.0]);

    pl.set_task("pick up the block and put it on the target");
    gripper.open().await?;
    arm.move_j_pose(down(block.position(), 0.15)).await?;
    arm.move_l(down(block.position(), 0.026)).await?;
    if !gripper.close().force(200).await?.object_detected {
        return Err("the gripper closed on nothing".into());
    }
    pl.wait_seconds(0.1).await?; // a fresh frame of the settled grasp
    for (digit, side) in digits.iter().zip(["left", "right"]) {
        let contact = digit.contact()?;
        let path = format!("{out}/digit_{side}.png");
        digit.read().save(&path)?;
        pl.log(format!(
            "{side} DIGIT: {:.2} mm deep over {:.1} mm² → {path}",
            contact.max_indentation * 1e3,
            contact.area * 1e6
        ));
        if !contact.in_contact {
            return Err(format!("the {side} DIGIT feels nothing while the block is held").into());
        }
    }
    arm.move_l(down(block.position(), 0.15)).await?;
    arm.move_l(down(target.position(), 0.15)).await?;
    arm.move_l(down(target.position(), 0.03)).await?;
    gripper.open().await?;
    arm.move_l(down(target.position(), 0.15)).await?;
    pl.log(format!(
        "t = {:.2} s: the block is on the target",
        pl.time()
    ));
    Ok(())
}
