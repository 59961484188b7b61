//! Worlds: roots to build environments on.

mod tactile_rig;

pub use tactile_rig::{Press, PressError, Sample, TactileRigWorld};

use yarok_core::component::{Component, Declaration};

use crate::cameras::Cam;
use crate::grippers::Robotiq2f85;
use crate::robots::AnetA30;
use crate::robots::ur::Ur5e;
use crate::tactile_sensors::{Digit, GelTip};
use crate::toys::{Block, Rope, Spot, TumbleTower};

/// A floor (`floor_size` metres from the centre to each edge, default 2), a sky and a sun;
/// angles in radians. Extend it (`Declaration::extends::<EmptyWorld>()`) to build a world.
#[derive(Debug, Clone)]
pub struct EmptyWorld;

impl Component for EmptyWorld {
    fn declaration() -> Declaration {
        Declaration::new("empty_world")
            .default("floor_size", 2.0)
            .template(include_str!("empty_world.xml"))
    }
}

/// The Anet A30 printer carrying a downward-looking camera on its head, over a tumble tower of
/// `rows` layers standing on the bed.
///
/// Paths: `/printer`, `/printer/cam`, `/tower`.
#[derive(Debug, Clone)]
pub struct PrinterWorld;

impl Component for PrinterWorld {
    fn declaration() -> Declaration {
        Declaration::new("printer_world")
            .extends::<EmptyWorld>()
            .uses::<AnetA30>()
            .uses::<Cam>()
            .uses::<TumbleTower>()
            .default("rows", 4)
            .template(
                r#"<mujoco>
                     <worldbody>
                       <anet_a30 name="printer">
                         <cam name="cam" parent="head" width="320" height="240" fovy="60"/>
                       </anet_a30>
                       <tumble-tower name="tower" rows="{rows}" pos="{[-0.42, -0.32, 0]}"/>
                     </worldbody>
                   </mujoco>"#,
            )
    }
}

/// An [`EmptyWorld`] with a tumble tower of `rows` layers (default 8) at `/tower`.
#[derive(Debug, Clone)]
pub struct TowerWorld;

impl Component for TowerWorld {
    fn declaration() -> Declaration {
        Declaration::new("tower_world")
            .extends::<EmptyWorld>()
            .uses::<TumbleTower>()
            .default("rows", 8)
            .template(r#"<mujoco><worldbody><tumble-tower name="tower" rows="{rows}"/></worldbody></mujoco>"#)
    }
}

/// Pick and place: a table (top at `table_height`, default 0.4 m) with a UR5e on a stand at its
/// edge and a Robotiq 2F-85 on the arm's flange, its TCP at the gripper's pinch point; three
/// blocks (`sizes`, default 5, 4 and 3 cm; `blocks = false` leaves them out) on the table and a
/// spot to stack them on at `target` (x, y); `sensors = "digit"` puts a DIGIT on each pad
/// ([`DigitWorld`]), `"geltip"` a GelTip along each finger; `rope` lays a rope on the table
/// ([`GelTipWorld`]).
///
/// Paths: `/arm`, `/arm/gripper`, `/large`, `/medium`, `/small`, `/target`; the camera `overview`
/// looks at the table from the front right (for recordings). The arm's base frame
/// is the world frame raised to the table top.
#[derive(Debug, Clone)]
pub struct PickAndPlaceWorld;

impl Component for PickAndPlaceWorld {
    fn declaration() -> Declaration {
        Declaration::new("pick_and_place_world")
            .extends::<EmptyWorld>()
            .uses::<Ur5e>()
            .uses::<Robotiq2f85>()
            .uses::<Block>()
            .uses::<Spot>()
            .uses::<Digit>()
            .uses::<GelTip>()
            .uses::<Rope>()
            .default("table_height", 0.4)
            .default("sizes", [0.05, 0.04, 0.03])
            .default("blocks", true)
            .default("sensors", "none")
            .default("rope", false)
            .default("target", [0.42, 0.38])
            .default("start", [0.0, -1.9, 1.9, -1.57, -1.57, 0.0])
            .template(include_str!("pick_and_place.xml"))
    }
}

/// Where [`DigitWorld`]'s arm starts (joint positions, radians): ready, its gripper pointing
/// down 15 cm above the table over the middle of the blocks' start region — so a grasp is a
/// short move from the start, as a learned policy best imitates it.
pub const DIGIT_WORLD_START: [f64; 6] = [
    2.93,
    -1.23,
    1.67,
    -2.01,
    -std::f64::consts::FRAC_PI_2,
    -1.78,
];

/// [`PickAndPlaceWorld`] with a DIGIT on each of the gripper's pads (`/arm/gripper/left_digit`,
/// `/arm/gripper/right_digit`), sensing the grasped block from both sides. The DIGITs take 18 mm
/// of each finger's stroke, so the blocks are 4, 3.5 and 3 cm. Its arm starts ready above the
/// blocks ([`DIGIT_WORLD_START`]).
#[derive(Debug, Clone)]
pub struct DigitWorld;

impl Component for DigitWorld {
    fn declaration() -> Declaration {
        Declaration::new("digit_world")
            .extends::<PickAndPlaceWorld>()
            .default("sensors", "digit")
            .default("sizes", [0.04, 0.035, 0.03])
            .default("start", DIGIT_WORLD_START)
            .template("<mujoco/>")
    }
}

/// [`PickAndPlaceWorld`] with a GelTip along each of the gripper's fingers
/// (`/arm/gripper/left_geltip`, `/arm/gripper/right_geltip`; each tube takes 30 mm of its
/// finger's stroke) and, instead of the blocks, a rope of 20 segments lying along +x
/// (`/rope`), its first 8 cm on a 3 cm high peg (`peg`) and the rest draped to the table: the
/// GelTips' 30 mm tubes can pinch its end from the sides, which they cannot do to a 12 mm rope
/// lying flat (their domes' equators are 15 mm above the table).
#[derive(Debug, Clone)]
pub struct GelTipWorld;

impl Component for GelTipWorld {
    fn declaration() -> Declaration {
        Declaration::new("geltip_world")
            .extends::<PickAndPlaceWorld>()
            .default("sensors", "geltip")
            .default("blocks", false)
            .default("rope", true)
            .template("<mujoco/>")
    }
}
