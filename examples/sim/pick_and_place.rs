//! A UR5e with a Robotiq 2F-85 stacks three blocks, largest first, on the target spot: for
//! each block it moves above it, goes straight down, closes, lifts, carries it over the stack,
//! lowers it onto the stack and lets go. Exits non-zero if a block ends more than 1 cm from its
//! place in the stack or falls off the table. The behaviour is
//! [`demos::stack`](yarok::components::demos::stack) (`yarok-components/src/demos/pick_and_place.rs`),
//! which `yarok run pick_and_place_world` runs too.
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
//!
//! Recorded for Foxglove and others (joint states, body poses, the overview camera, the log
//! lines) and filmed:
//!
//! ```text
//! cargo run --release --example pick_and_place -- --set plugins/mcap/path='"run.mcap"' \
//!   --set 'plugins/mcap/cameras=["overview"]' --set plugins/video/path='"run.mp4"'
//! ```

use yarok::components::demos;
use yarok::components::worlds::PickAndPlaceWorld;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = std::time::Instant::now();
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .args(std::env::args_os().skip(1))?
        .behaviour(demos::stack)
        .run()?;
    println!(
        "stacked in {:.1} s of wall time",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
