//! A UR5e with a Robotiq 2F-85 stacks three blocks, largest first, on the target spot: for
//! each block it moves above it, goes straight down, closes, lifts, carries it over the stack,
//! lowers it onto the stack and lets go. Exits non-zero if a block ends more than 1 cm from its
//! place in the stack or falls off the table.
//!
//! ```text
//! cargo run --release --example pick_and_place
//! ```
//!
//! The same behaviour drives a real UR5e and 2F-85 (the blocks where the world places them;
//! measure yours and set `/large/pos` …): every motion and grasp must complete, and the
//! blocks' positions are checked in `sim` only.
//!
//! ```text
//! cargo run --release --example pick_and_place -- --env real \
//!   --set 'interfaces/arm/host="192.168.1.10"' --set 'interfaces/arm/gripper/host="192.168.1.10"'
//! ```

use std::f64::consts::PI;

use yarok::Pl;
use yarok::components::grippers::Robotiq2f85;
use yarok::components::robots::ur::{Ur5e, pose_from_vector};
use yarok::components::toys::{Block, Spot};
use yarok::components::worlds::PickAndPlaceWorld;

/// The blocks, largest first: the order they are stacked in.
const BLOCKS: [&str; 3] = ["/large", "/medium", "/small"];

/// How high above a grasp or a place the TCP passes (metres).
const CLEARANCE: f64 = 0.12;

/// How far above the table the TCP grips (metres): low enough to hold the smallest block,
/// high enough that the pads clear the table.
const GRIP_HEIGHT: f64 = 0.026;

/// The TCP pose at `position` (world frame, metres), pointing down, in the arm's base frame
/// (the world raised by the table's height).
fn down_at(position: [f64; 3], table: f64) -> yarok::nalgebra::Isometry3<f64> {
    pose_from_vector([position[0], position[1], position[2] - table, PI, 0.0, 0.0])
}

async fn stack(pl: Pl) -> yarok::BehaviourResult {
    let arm: Ur5e = pl.get("/arm")?;
    let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
    let target: Spot = pl.get("/target")?;
    let blocks: Vec<Block> = BLOCKS
        .iter()
        .map(|path| pl.get(path))
        .collect::<Result<_, _>>()?;
    let table = target.position()[2];
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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = std::time::Instant::now();
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .args(std::env::args().skip(1))?
        .behaviour(stack)
        .run()?;
    println!(
        "stacked in {:.1} s of wall time",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
