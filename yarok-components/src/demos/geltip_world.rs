//! The GelTipWorld demo: a rope pulled across the table.

use std::f64::consts::PI;

use yarok_core::runtime::{BehaviourResult, Pl};

use super::out_folder;
use crate::grippers::Robotiq2f85;
use crate::robots::ur::{Ur5e, pose_from_vector};
use crate::tactile_sensors::GelTip;
use crate::toys::{Rope, Spot};

/// How high above the rope's end the TCP grips: the GelTips' tubes (not their domes) at the
/// rope, so the grip is a side pinch. Pinched under their domes' equators, a rope is wedged out
/// downward as soon as it is lifted.
const GRIP_ABOVE_ROPE: f64 = 0.005;

/// How far the rope's end is lifted before the pull: clear of the peg it rested on.
const LIFT: f64 = 0.05;

/// In a [`GelTipWorld`](crate::worlds::GelTipWorld): grasps the rope by the end that rests on
/// a peg, lifts it and pulls it 25 cm across the table; saves what each GelTip sees while holding the rope
/// (`OUT/geltip_left.png`, `OUT/geltip_right.png`, OUT the behaviour's setting `out`, default
/// `out`). Fails if the rope's end moved less than 10 cm.
pub async fn pull(pl: Pl) -> BehaviourResult {
    let arm: Ur5e = pl.get("/arm")?;
    let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
    let sensors: [GelTip; 2] = [
        pl.get("/arm/gripper/left_geltip")?,
        pl.get("/arm/gripper/right_geltip")?,
    ];
    let rope: Rope = pl.get("/rope")?;
    let table = pl.get::<Spot>("/target")?.position()[2];
    let out = out_folder(&pl)?;
    // The TCP pointing down (fingers closing across the rope), `z` above the table.
    let down = |x: f64, y: f64, z: f64| pose_from_vector([x, y, z, PI, 0.0, 0.0]);

    let [end, _] = rope.ends();
    let [x, y, z] = end;
    let grip_height = z - table + GRIP_ABOVE_ROPE;
    gripper.open().await?;
    // Above the rope's end with the shoulder lifted and the elbow up, clear of the table: of
    // the arm's inverse solutions, the nearest of that posture.
    let current = arm.q();
    let above = arm
        .kinematics()
        .solutions(&down(x, y, 0.12), &current)
        .into_iter()
        .filter(|q| q[1] < 0.0 && q[1] > -PI && q[2] > 0.0)
        .min_by(|a, b| motion(a, &current).total_cmp(&motion(b, &current)))
        .ok_or("the rope's end is out of reach")?;
    arm.move_j(above).await?;
    arm.move_l(down(x, y, grip_height)).await?;
    if !gripper.close().force(60).await?.object_detected {
        return Err("the gripper closed on nothing".into());
    }
    pl.wait_seconds(0.1).await?;
    for (sensor, side) in sensors.iter().zip(["left", "right"]) {
        let path = format!("{out}/geltip_{side}.png");
        crate::probe_images::save_png(sensor.read(), &path)?;
        let contact = sensor.contact()?;
        pl.log(format!(
            "{side} GelTip: {:.2} mm deep over {:.1} mm² → {path}",
            contact.max_indentation * 1e3,
            contact.area * 1e6
        ));
    }
    arm.move_l(down(x, y, grip_height + LIFT)).await?;
    arm.move_l(down(x, y + 0.25, grip_height + LIFT))
        .speed(0.1)
        .await?;
    let [moved, _] = rope.ends();
    let distance = (moved[0] - end[0]).hypot(moved[1] - end[1]);
    pl.log(format!(
        "t = {:.2} s: the rope's end moved {:.1} cm (table at {table:.2} m)",
        pl.time(),
        distance * 100.0
    ));
    gripper.open().await?;
    if distance < 0.10 {
        return Err(format!("the rope's end moved only {:.1} cm", distance * 100.0).into());
    }
    Ok(())
}

/// How far (sum of joint angles, radians) `q` is from `current`.
fn motion(q: &[f64; 6], current: &[f64; 6]) -> f64 {
    q.iter().zip(current).map(|(a, b)| (a - b).abs()).sum()
}
