//! A platform awaited inside an application's own single-threaded tokio runtime, beside the
//! application's other tasks on the same `LocalSet`.
//!
//! ```text
//! cargo run --example local_set
//! ```

use std::cell::Cell;
use std::rc::Rc;

use yarok::components::robots::AnetA30;
use yarok::components::worlds::PrinterWorld;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()?;
    let local = tokio::task::LocalSet::new();
    let heartbeats = Rc::new(Cell::new(0));
    let counter = Rc::clone(&heartbeats);
    local.spawn_local(async move {
        loop {
            counter.set(counter.get() + 1);
            tokio::task::yield_now().await;
        }
    });
    let platform = yarok::platform()
        .world::<PrinterWorld>()
        .behaviour(|pl| async move {
            let printer: AnetA30 = pl.get("/printer")?;
            let target = printer.move_to([200.0, 100.0, 300.0]);
            pl.wait(|| printer.is_at(target)).timeout(10.0).await?;
            println!(
                "arrived at {:?} mm after {:.2} s of simulated time",
                printer.at().map(f64::round),
                pl.time()
            );
            Ok(())
        })
        .build()?;
    local.block_on(&runtime, platform.run_local())?;
    println!(
        "the application's own task ran {} times meanwhile",
        heartbeats.get()
    );
    assert!(heartbeats.get() > 0);
    Ok(())
}
