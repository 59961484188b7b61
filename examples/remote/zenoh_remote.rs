//! A world in one process driven by a behaviour in another, through the Zenoh bridge: this
//! program starts itself again as the world (PickAndPlaceWorld, paced to the wall clock, its
//! bridge listening on loopback), then, as a Zenoh client, follows the arm's state, moves it
//! through two poses and closes and opens the gripper, and stops the world.
//!
//! ```text
//! cargo run --release --features zenoh --example zenoh_remote
//! ```
//!
//! The same from Python: `scripts/peers/zenoh_client.py`; key space: `ZenohBridge`'s docs.

use std::process::Command;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use yarok::components::worlds::PickAndPlaceWorld;
use yarok::components::zenoh::{self, Wait};

const ENDPOINT: &str = "tcp/127.0.0.1:7448";

/// The world's side: the bridge, and a behaviour that only waits.
fn world() -> Result<(), yarok::BoxError> {
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .set("platform/realtime=true")?
        .set(&format!("plugins/zenoh/listen=[{ENDPOINT:?}]"))?
        .behaviour(|pl| async move {
            pl.wait_forever().await?;
            Ok(())
        })
        .run()?;
    Ok(())
}

/// Waits until `condition` holds of a received JSON message, at most `seconds`.
fn until(
    messages: &mpsc::Receiver<(String, serde_json::Value)>,
    seconds: f64,
    mut condition: impl FnMut(&str, &serde_json::Value) -> bool,
) -> Result<(), String> {
    let deadline = Instant::now() + Duration::from_secs_f64(seconds);
    while Instant::now() < deadline {
        if let Ok((key, value)) = messages.recv_timeout(Duration::from_millis(100))
            && condition(&key, &value)
        {
            return Ok(());
        }
    }
    Err(format!("nothing came within {seconds} s"))
}

fn main() -> Result<(), yarok::BoxError> {
    if std::env::args_os().nth(1).is_some_and(|arg| arg == "world") {
        return world();
    }
    let mut child = Command::new(std::env::current_exe()?)
        .arg("world")
        .spawn()?;
    let mut config = zenoh::Config::default();
    config.insert_json5("mode", "\"client\"")?;
    config.insert_json5("connect/endpoints", &format!("[{ENDPOINT:?}]"))?;
    config.insert_json5("scouting/multicast/enabled", "false")?;
    // The world needs a moment to start listening.
    let session = (0..100)
        .find_map(|_| {
            std::thread::sleep(Duration::from_millis(100));
            zenoh::open(config.clone()).wait().ok()
        })
        .ok_or("no world to connect to")?;
    let (sender, messages) = mpsc::channel();
    let _subscriber = session
        .declare_subscriber("yarok/world/**")
        .callback(move |sample| {
            let value = serde_json::from_slice(&sample.payload().to_bytes()).unwrap_or_default();
            let _ = sender.send((sample.key_expr().as_str().to_owned(), value));
        })
        .wait()?;
    let command = |path: &str, body: serde_json::Value| {
        session
            .put(format!("yarok/world{path}/command"), body.to_string())
            .wait()
    };
    for target in [
        [0.4, -1.6, 1.7, -1.65, -1.57, 0.0],
        [-0.3, -1.9, 1.9, -1.57, -1.57, 0.3],
    ] {
        command(
            "/arm",
            serde_json::json!({ "move_j": target, "speed": 1.5 }),
        )?;
        let started = Instant::now();
        until(&messages, 20.0, |key, state| {
            key == "yarok/world/arm/state"
                && state["q"].as_array().is_some_and(|q| {
                    q.iter()
                        .zip(target)
                        .all(|(a, b)| (a.as_f64().unwrap_or(f64::NAN) - b).abs() < 0.005)
                })
        })?;
        println!(
            "arm at {target:?} after {:.2} s",
            started.elapsed().as_secs_f64()
        );
    }
    for (what, body) in [
        ("closed", serde_json::json!({ "close": true })),
        ("opened", serde_json::json!({ "open": true })),
    ] {
        command("/arm/gripper", body)?;
        until(&messages, 10.0, |key, reply| {
            key == "yarok/world/arm/gripper/reply" && reply["ok"] == true
        })?;
        until(&messages, 10.0, |key, state| {
            key == "yarok/world/arm/gripper/state" && state["moving"] == false
        })?;
        println!("gripper {what}");
    }
    command("", serde_json::json!({ "stop": true }))?;
    let status = child.wait()?;
    println!("the world ended: {status}");
    Ok(())
}
