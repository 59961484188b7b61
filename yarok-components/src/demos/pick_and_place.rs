//! The pick-and-place demo: the arm stacks the blocks.

use std::f64::consts::PI;

use nalgebra::Isometry3;
use yarok_core::runtime::{BehaviourResult, Pl};

use crate::grippers::{ParallelGripper, Robotiq2f85};
use crate::robots::ur::{Arm, Ur5e, pose_from_vector};
use crate::toys::{Block, Spot};

/// The blocks, largest first: the order they are stacked in.
const BLOCKS: [&str; 3] = ["/large", "/medium", "/small"];

/// How high above a grasp or a place the TCP passes (metres).
const CLEARANCE: f64 = 0.12;

/// How far above the table the TCP grips (metres): low enough to hold the smallest block,
/// high enough that the pads clear the table.
const GRIP_HEIGHT: f64 = 0.026;

/// The TCP pose at `position` (world frame, metres), pointing down, in the arm's base frame
/// (the world raised by the table's height).
fn down_at(position: [f64; 3], table: f64) -> Isometry3<f64> {
    pose_from_vector([position[0], position[1], position[2] - table, PI, 0.0, 0.0])
}

/// Stacks the blocks of a [`PickAndPlaceWorld`](crate::worlds::PickAndPlaceWorld), largest
/// first, on the target spot: for each block the arm moves above it, goes straight down,
/// closes, lifts, carries it over the stack, lowers it onto the stack and lets go. In `sim`,
/// fails if a block ends more than 1 cm from its place or falls off the table; elsewhere (the
/// blocks are not measured) every motion and grasp must complete.
pub async fn stack(pl: Pl) -> BehaviourResult {
    let arm: Ur5e = pl.get("/arm")?;
    let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
    stack_with(&pl, &arm, &gripper).await
}

/// [`stack`] with any UR arm and 2F-85 (a world of the same layout whose arm and gripper are
/// other models, e.g. MuJoCo Menagerie's): the blocks at `/large`, `/medium` and `/small`, the
/// spot at `/target`, the arm's base frame level with the table top, its TCP at the pinch point.
pub async fn stack_with(pl: &Pl, arm: &Arm, gripper: &ParallelGripper) -> BehaviourResult {
    let target: Spot = pl.get("/target")?;
    let blocks: Vec<Block> = BLOCKS
        .iter()
        .map(|path| pl.get(path))
        .collect::<Result<_, _>>()?;
    let table = target.position()[2];
    pl.set_task("stack the blocks on the target, largest first");
    gripper.open().await?;
    // Round the base to the table with a joint motion; straight lines from then on.
    let [x, y, _] = blocks[0].position();
    arm.move_j_pose(down_at([x, y, table + 0.2], table)).await?;
    let mut stack_top = table;
    let mut places = Vec::new();
    for (name, block) in BLOCKS.iter().zip(&blocks) {
        let [x, y, _] = block.position();
        let grip = table + GRIP_HEIGHT.min(block.size() / 2.0).max(GRIP_HEIGHT);
        arm.move_l(down_at([x, y, grip + CLEARANCE], table)).await?;
        arm.move_l(down_at([x, y, grip], table)).await?;
        let gripped = gripper.close().force(200).await?;
        if !gripped.object_detected {
            return Err(format!("{name}: the gripper closed on nothing").into());
        }
        // The block rises as far above the stack as its grip was above the table.
        let [tx, ty, _] = target.position();
        let held_above_bottom = grip - table;
        let place = stack_top + held_above_bottom + 0.003;
        arm.move_l(down_at([x, y, grip + CLEARANCE], table)).await?;
        arm.move_l(down_at([tx, ty, place + CLEARANCE], table))
            .await?;
        arm.move_l(down_at([tx, ty, place], table)).await?;
        gripper.open().await?;
        arm.move_l(down_at([tx, ty, place + CLEARANCE], table))
            .await?;
        places.push([tx, ty, stack_top + block.size() / 2.0]);
        stack_top += block.size();
        pl.log(format!("t = {:5.2} s  {name} stacked", pl.time()));
    }
    if pl.environment() != "sim" {
        pl.log("every motion and grasp completed");
        return Ok(());
    }
    pl.wait_seconds(0.5).await?;
    for ((name, block), place) in BLOCKS.iter().zip(&blocks).zip(places) {
        let at = block.position();
        let off = (0..3)
            .map(|i| (at[i] - place[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        pl.log(format!("{name}: {:.1} mm from its place", off * 1000.0));
        if off > 0.01 || at[2] < table {
            return Err(format!(
                "{name} is {:.1} mm from its place {place:?}: at {at:?}",
                off * 1000.0
            )
            .into());
        }
    }
    Ok(())
}
