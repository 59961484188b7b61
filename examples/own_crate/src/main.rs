//! Runs the showroom in `sim` (or `--env mock`) with the quarter turn.

use my_turntable::{Showroom, quarter_turn};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    yarok::platform()
        .world::<Showroom>()
        .args(std::env::args_os().skip(1))?
        .behaviour(|pl| async move {
            let angle = quarter_turn(pl.clone()).await?;
            pl.log(format!("the turntable is at {angle:.3} rad"));
            Ok(())
        })
        .run()?;
    Ok(())
}
