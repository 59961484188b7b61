//! Worlds: roots to build environments on.

use yarok_core::component::{Component, Declaration};

use crate::cameras::Cam;
use crate::robots::AnetA30;
use crate::toys::TumbleTower;

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
