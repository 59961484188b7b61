//! DigitWorld: the UR5e with a Robotiq 2F-85 whose pads carry DIGIT tactile sensors picks the
//! medium block and puts it on the target; once the block is grasped, it saves what each DIGIT
//! sees (`out/digit_left.png`, `out/digit_right.png`). Exits non-zero if a sensor feels nothing
//! while the block is held.
//!
//! ```text
//! cargo run --release --example digit_world [-- --set behaviour/out="shots"]
//! ```

use std::f64::consts::PI;

use yarok::Pl;
use yarok::components::grippers::Robotiq2f85;
use yarok::components::robots::ur::{Ur5e, pose_from_vector};
use yarok::components::tactile_sensors::Digit;
use yarok::components::toys::{Block, Spot};
use yarok::components::worlds::DigitWorld;

async fn feel(pl: Pl) -> yarok::BehaviourResult {
    let arm: Ur5e = pl.get("/arm")?;
    let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
    let digits: [Digit; 2] = [
        pl.get("/arm/gripper/left_digit")?,
        pl.get("/arm/gripper/right_digit")?,
    ];
    let (block, target): (Block, Spot) = (pl.get("/medium")?, pl.get("/target")?);
    let Some(out) = pl.config().get("out").and_then(|out| out.as_str()) else {
        return Err("behaviour/out must be a folder".into());
    };
    std::fs::create_dir_all(out)?;
    // The TCP pointing down, `z` above the table, in the arm's base frame.
    let down = |[x, y, _]: [f64; 3], z: f64| pose_from_vector([x, y, z, PI, 0.0, 0.0]);

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
        println!(
            "{side} DIGIT: {:.2} mm deep over {:.1} mm² → {path}",
            contact.max_indentation * 1e3,
            contact.area * 1e6
        );
        if !contact.in_contact {
            return Err(format!("the {side} DIGIT feels nothing while the block is held").into());
        }
    }
    arm.move_l(down(block.position(), 0.15)).await?;
    arm.move_l(down(target.position(), 0.15)).await?;
    arm.move_l(down(target.position(), 0.03)).await?;
    gripper.open().await?;
    arm.move_l(down(target.position(), 0.15)).await?;
    println!("t = {:.2} s: the block is on the target", pl.time());
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = std::time::Instant::now();
    yarok::platform()
        .world::<DigitWorld>()
        .behaviour_default("out", "out")
        .args(std::env::args().skip(1))?
        .behaviour(feel)
        .run()?;
    println!(
        "done in {:.1} s of wall time",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
