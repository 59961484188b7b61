//! The Anet A30 printer carries a camera over a tumble tower: a behaviour moves the head through
//! a few poses, waits for it to arrive (in simulated time), and saves what the camera sees at
//! each pose as PNG.
//!
//! ```text
//! cargo run --release --example printer_camera [-- --set /tower/rows=6 --set behaviour/out="shots"]
//! ```

use yarok::Pl;
use yarok::components::cameras::Cam;
use yarok::components::robots::AnetA30;
use yarok::components::worlds::PrinterWorld;

/// Head positions in millimetres: around the tower, then straight above it.
const POSES: [[f64; 3]; 4] = [
    [40.0, 40.0, 420.0],
    [280.0, 40.0, 420.0],
    [280.0, 280.0, 420.0],
    [160.0, 160.0, 400.0],
];

async fn survey(pl: Pl) -> yarok::BehaviourResult {
    let printer: AnetA30 = pl.get("/printer")?;
    let camera: Cam = pl.get("/printer/cam")?;
    let Some(out) = pl.config().get("out").and_then(|out| out.as_str()) else {
        return Err("behaviour/out must be a folder".into());
    };
    std::fs::create_dir_all(out)?;
    for (index, pose) in POSES.into_iter().enumerate() {
        let target = printer.move_to(pose);
        pl.wait(|| printer.is_at(target)).timeout(10.0).await?;
        pl.wait_seconds(0.2).await?; // let the head settle before the shot
        let path = format!("{out}/printer_camera_{index}.png");
        camera.read()?.save(&path)?;
        println!(
            "t = {:5.2} s  head at {:?} mm  → {path}",
            pl.time(),
            printer.at().map(|mm| mm.round())
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = std::time::Instant::now();
    let platform = yarok::platform()
        .world::<PrinterWorld>()
        .behaviour_default("out", "out")
        .args(std::env::args().skip(1))?
        .behaviour(survey)
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
