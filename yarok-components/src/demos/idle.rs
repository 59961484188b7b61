//! The demo of worlds without a task: time passes.

use yarok_core::runtime::{BehaviourResult, Pl};

/// Lets the world run for the behaviour's setting `seconds` of platform time and says how far
/// it got.
pub async fn idle(pl: Pl) -> BehaviourResult {
    let seconds = pl
        .config()
        .get("seconds")
        .and_then(|seconds| seconds.as_f64())
        .ok_or("behaviour/seconds must be a number")?;
    pl.wait_seconds(seconds).await?;
    pl.log(format!("t = {:.2} s: {} ticks", pl.time(), pl.ticks()));
    Ok(())
}
