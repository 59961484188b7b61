//! The Anet A30 printer homes and traces a square, reporting where the head arrived at each
//! corner — in simulation by default, on a real printer with `--env real`:
//!
//! ```text
//! cargo run --example printer_square
//! cargo run --example printer_square -- --env real --set 'interfaces/printer/port="/dev/ttyUSB0"'
//! ```
//!
//! `--set behaviour/side=80` sets the square's side (mm), `--set behaviour/laps=3` how many
//! times it is traced. On a real printer the head moves at the interface's `feed` (mm/s,
//! default 50) after homing (`home = false` to skip it); Ctrl-C stops the printer at once.

use yarok::components::robots::AnetA30;
use yarok::components::worlds::EmptyWorld;
use yarok::{Component, Declaration};

/// The printer alone, on the floor.
struct PrinterSquareWorld;

impl Component for PrinterSquareWorld {
    fn declaration() -> Declaration {
        Declaration::new("printer_square_world")
            .extends::<EmptyWorld>()
            .uses::<AnetA30>()
            .template(r#"<mujoco><worldbody><anet_a30 name="printer"/></worldbody></mujoco>"#)
    }
}

async fn trace_square(pl: yarok::Pl) -> yarok::BehaviourResult {
    let printer: AnetA30 = pl.get("/printer")?;
    let number = |key: &str| pl.config().get(key).and_then(|value| value.as_f64());
    let (Some(side), Some(laps)) = (number("side"), number("laps")) else {
        return Err("behaviour/side and behaviour/laps must be numbers".into());
    };
    let (x0, y0, z) = (100.0, 100.0, 10.0);
    for _ in 0..laps as u64 {
        for [dx, dy] in [
            [0.0, 0.0],
            [side, 0.0],
            [side, side],
            [0.0, side],
            [0.0, 0.0],
        ] {
            let target = printer.move_to([x0 + dx, y0 + dy, z]);
            pl.wait(|| printer.is_at(target)).timeout(60.0).await?;
            let [x, y, z] = printer.at();
            println!(
                "t = {:6.2} s: head at ({x:.2}, {y:.2}, {z:.2}) mm",
                pl.time()
            );
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    yarok::platform()
        .world::<PrinterSquareWorld>()
        .behaviour_default("side", 50.0)
        .behaviour_default("laps", 1)
        .args(std::env::args_os().skip(1))?
        .behaviour(trace_square)
        .run()?;
    Ok(())
}
