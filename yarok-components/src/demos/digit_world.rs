//! The DigitWorld demo: what the DIGITs feel of a grasped block.

use std::f64::consts::PI;

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use yarok_core::runtime::{BehaviourResult, Pl};

use super::out_folder;
use crate::grippers::Robotiq2f85;
use crate::robots::ur::{Ur5e, pose_from_vector};
use crate::tactile::noise::SplitMix64;
use crate::tactile_sensors::Digit;
use crate::toys::{Block, Spot};

/// Where [`demonstrate`] starts the medium block, in the world frame: `x` and `y` ranges
/// (metres), within the arm's reach and clear of the other blocks; its yaw is drawn within
/// ±[`START_YAW`]. yarok's Python `PickPlace` task draws its starts from the same region.
pub const START_REGION: [[f64; 2]; 2] = [[0.56, 0.68], [-0.12, 0.06]];

/// The largest yaw (radians) [`demonstrate`] starts the block at.
pub const START_YAW: f64 = std::f64::consts::FRAC_PI_4;

/// How long [`demonstrate`]'s arm stays still where it grasps and where it lets go, before the
/// gripper moves (seconds).
const SETTLE: f64 = 0.25;

/// The TCP pointing down, `z` above the table, over `[x, y]` of the arm's base frame.
fn down(position: [f64; 3], z: f64) -> Isometry3<f64> {
    down_turned(position, z, 0.0)
}

/// [`down`], the gripper turned `yaw` radians about the vertical (to grasp a turned block
/// across its faces).
fn down_turned([x, y, _]: [f64; 3], z: f64, yaw: f64) -> Isometry3<f64> {
    let pointing_down = pose_from_vector([x, y, z, PI, 0.0, 0.0]);
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw);
    Isometry3::from_parts(pointing_down.translation, turn * pointing_down.rotation)
}

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
        crate::probe_images::save_png(digit.read(), &path)?;
        pl.log(format!(
            "{side} DIGIT: {:.2} mm deep over {:.1} mm² → {path}",
            contact.max_indentation * 1e3,
            contact.area * 1e6
        ));
        if !contact.in_contact {
            return Err(format!("the {side} DIGIT feels nothing while the block is held").into());
        }
    }
    put_on_target(&pl, &arm, &gripper, &block, &target, 0.0).await?;
    pl.log(format!(
        "t = {:.2} s: the block is on the target",
        pl.time()
    ));
    Ok(())
}

/// Carries the grasped `block` to `target`, the gripper turned `yaw`, lets it go there and
/// lifts the gripper clear.
async fn put_on_target(
    pl: &Pl,
    arm: &Ur5e,
    gripper: &Robotiq2f85,
    block: &Block,
    target: &Spot,
    yaw: f64,
) -> BehaviourResult {
    arm.move_l(down_turned(block.position(), 0.15, yaw)).await?;
    arm.move_l(down_turned(target.position(), 0.15, yaw))
        .await?;
    arm.move_l(down_turned(target.position(), 0.03, yaw))
        .await?;
    pl.wait_seconds(SETTLE).await?;
    gripper.open().await?;
    arm.move_l(down_turned(target.position(), 0.15, yaw))
        .await?;
    Ok(())
}

/// [`demonstrate`]'s behaviour settings.
#[derive(serde::Deserialize)]
struct DemonstrateSettings {
    episodes: u64,
    seed: u64,
}

/// In a [`DigitWorld`](crate::worlds::DigitWorld): demonstrations for learning — the
/// behaviour's `episodes` episodes (default 10), each the world back at its start, the medium
/// block put at rest at a place and yaw drawn from `seed` (default 0) and the episode's
/// number within [`START_REGION`] and ±[`START_YAW`], then picked and put on the target, the
/// gripper opened and lifted clear. The same seed gives the same starts, in any shard.
///
/// With `yarok run digit_world --behaviour demonstrate --dataset DIR`, each episode is an
/// episode of the dataset, as yarok's Python `yarok/PickPlace-v0` environment observes it.
pub async fn demonstrate(pl: Pl) -> BehaviourResult {
    let DemonstrateSettings { episodes, seed } = pl.config().deserialize()?;
    let arm: Ur5e = pl.get("/arm")?;
    let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
    let (block, target): (Block, Spot) = (pl.get("/medium")?, pl.get("/target")?);
    pl.set_task("pick up the block and put it on the target");
    for (number, _) in pl.shard().select(0..episodes) {
        pl.begin_episode(number as u64)?;
        let mut draw = SplitMix64::new(seed ^ (number as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let [[x_low, x_high], [y_low, y_high]] = START_REGION;
        let [_, _, z] = block.position();
        let place = [draw.uniform(x_low, x_high), draw.uniform(y_low, y_high), z];
        let yaw = draw.uniform(-START_YAW, START_YAW);
        block.place(place, yaw)?;
        gripper.open().await?;
        // Above the block first as the arm starts (the inverse kinematics' nearest branch),
        // then turned along a line: a turned pose reached by a joint move may flip the arm.
        arm.move_j_pose(down(block.position(), 0.15)).await?;
        arm.move_l(down_turned(block.position(), 0.15, yaw)).await?;
        arm.move_l(down_turned(block.position(), 0.026, yaw))
            .await?;
        // Still for a moment before the gripper closes (and opens, below): a policy learns to
        // close once the arm is down, not as it arrives.
        pl.wait_seconds(SETTLE).await?;
        if !gripper.close().force(200).await?.object_detected {
            return Err(format!("episode {number}: the gripper closed on nothing").into());
        }
        put_on_target(&pl, &arm, &gripper, &block, &target, yaw).await?;
    }
    pl.end_episode();
    Ok(())
}
