//! The Anet A30 printer carries a camera over a tumble tower: a behaviour moves the head through
//! a few poses, waits for it to arrive (in simulated time), and saves what the camera sees at
//! each pose as PNG.
//! The behaviour is [`demos::survey`](yarok::components::demos::survey), which `yarok run
//! printer_world` runs too.
//!
//! ```text
//! cargo run --release --example printer_camera [-- --set /tower/rows=6 --set behaviour/out="shots"]
//! ```

use yarok::components::demos;
use yarok::components::worlds::PrinterWorld;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = std::time::Instant::now();
    let platform = yarok::platform()
        .world::<PrinterWorld>()
        .behaviour_default("out", "out")
        .args(std::env::args_os().skip(1))?
        .behaviour(demos::survey)
        .build()?;
    let ticks_before = platform.pl().clone();
    platform.run()?;
    let seconds = started.elapsed().as_secs_f64();
    println!(
        "{} ticks ({:.2} s simulated) in {seconds:.2} s of wall time",
        ticks_before.ticks(),
        ticks_before.time()
    );
    Ok(())
}
