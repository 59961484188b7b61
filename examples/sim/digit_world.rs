//! DigitWorld: the UR5e with a Robotiq 2F-85 whose pads carry DIGIT tactile sensors picks the
//! medium block and puts it on the target; once the block is grasped, it saves what each DIGIT
//! sees (`out/digit_left.png`, `out/digit_right.png`). Exits non-zero if a sensor feels nothing
//! while the block is held.
//! The behaviour is [`demos::feel`](yarok::components::demos::feel), which `yarok run digit_world`
//! runs too.
//!
//! ```text
//! cargo run --release --example digit_world [-- --set behaviour/out="shots"]
//! ```

use yarok::components::demos;
use yarok::components::worlds::DigitWorld;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = std::time::Instant::now();
    yarok::platform()
        .world::<DigitWorld>()
        .behaviour_default("out", "out")
        .args(std::env::args_os().skip(1))?
        .behaviour(demos::feel)
        .run()?;
    println!(
        "done in {:.1} s of wall time",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
