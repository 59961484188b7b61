//! Toys: props to push, grasp and knock over.

mod block;
mod rope;

pub use block::{Block, Spot};
pub use rope::Rope;
use yarok_core::component::{Component, Declaration};

/// A tumble tower of `rows` layers (default 8) of three 0.08 × 0.24 × 0.056 m wooden blocks of
/// 0.1 kg, alternate layers turned a quarter turn, centred on (0.58, 0.48) with layers 0.061 m
/// apart and the bottom layer resting on z = 0, all shifted by `pos`.
///
/// Tag `tumble-tower`; config `rows` (integer), `pos` (three numbers, metres). The blocks are free
/// bodies, so the tower goes directly in `<worldbody>`.
#[derive(Debug)]
pub struct TumbleTower;

impl Component for TumbleTower {
    fn declaration() -> Declaration {
        Declaration::new("tumble-tower")
            .default("rows", 8)
            .default("pos", [0.0, 0.0, 0.0])
            .template(include_str!("tumble_tower.xml"))
    }
}
