//! A platform on its own thread, driven from a multi-threaded tokio application: the behaviour
//! streams the printer head's position over a channel; the application prints a few updates,
//! then stops the platform through its `Send` handle and awaits how it ended.
//!
//! ```text
//! cargo run --example threaded
//! ```

use yarok::components::robots::AnetA30;
use yarok::components::worlds::PrinterWorld;
use yarok::core::runtime::PlatformThread;

#[tokio::main(flavor = "multi_thread", worker_threads = 2)]
async fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (positions, mut updates) = tokio::sync::mpsc::unbounded_channel();
    let platform = PlatformThread::spawn(move || {
        yarok::platform()
            .world::<PrinterWorld>()
            .behaviour(move |pl| async move {
                let printer: AnetA30 = pl.get("/printer")?;
                for corner in [
                    [0.0, 0.0, 400.0],
                    [320.0, 0.0, 400.0],
                    [320.0, 320.0, 400.0],
                    [0.0, 320.0, 400.0],
                ]
                .iter()
                .cycle()
                {
                    let target = printer.move_to(*corner);
                    pl.wait(|| printer.is_at(target)).timeout(10.0).await?;
                    positions.send((pl.time(), printer.at()))?;
                }
                Ok(())
            })
    });
    let mut received = 0;
    while let Some((time, at)) = updates.recv().await {
        println!("t = {time:5.2} s: head at {:?} mm", at.map(f64::round));
        received += 1;
        if received == 5 {
            platform.stop();
            break;
        }
    }
    platform.finished().await?;
    println!("stopped after {received} corners");
    Ok(())
}
