//! GelTipWorld: the UR5e with a Robotiq 2F-85 whose fingers are GelTip sensors grasps a rope
//! lying on the table by one end and pulls it 25 cm across; it saves what each GelTip sees while
//! holding the rope (`out/geltip_left.png`, `out/geltip_right.png`). Exits non-zero if the rope's
//! end moved less than 10 cm.
//! The behaviour is [`demos::pull`](yarok::components::demos::pull), which `yarok run geltip_world`
//! runs too.
//!
//! ```text
//! cargo run --release --example geltip_world [-- --set behaviour/out="shots"]
//! ```

use yarok::components::demos;
use yarok::components::worlds::GelTipWorld;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = std::time::Instant::now();
    yarok::platform()
        .world::<GelTipWorld>()
        .behaviour_default("out", "out")
        .args(std::env::args_os().skip(1))?
        .behaviour(demos::pull)
        .run()?;
    println!(
        "done in {:.1} s of wall time",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
