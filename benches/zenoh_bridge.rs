//! The Zenoh bridge on loopback, for `many_worlds` (feature `zenoh`): PickAndPlaceWorld's ticks
//! per second without and with the bridge (states at 50 Hz of platform time), so its cost per
//! tick; and the round trip of a ping from a client in the same process to the world's bridge
//! and back (answered on the world's next tick), p50 and p99 of 2000.

use std::rc::Rc;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use yarok::components::plugins::{ZenohBridge, ZenohBridgeSettings};
use yarok::components::worlds::PickAndPlaceWorld;
use yarok::components::zenoh::{self, Wait};
use yarok::core::runtime::PlatformThread;

use super::measure::mean_times;

const SECONDS: f64 = 2.0;
const PINGS: usize = 2000;

fn bridge(endpoint: &str) -> ZenohBridge {
    ZenohBridge::new(ZenohBridgeSettings {
        listen: vec![endpoint.to_owned()],
        ..ZenohBridgeSettings::default()
    })
    .expect("valid settings")
}

/// PickAndPlaceWorld idle for `SECONDS`, with the bridge on `endpoint` or without; its ticks.
fn run(endpoint: Option<&str>) -> u64 {
    let ticks = Rc::new(std::cell::Cell::new(0));
    let counted = Rc::clone(&ticks);
    let mut platform =
        yarok::platform()
            .world::<PickAndPlaceWorld>()
            .behaviour(move |pl| async move {
                pl.wait_seconds(SECONDS).await?;
                counted.set(pl.ticks());
                Ok(())
            });
    if let Some(endpoint) = endpoint {
        platform = platform.plugin(bridge(endpoint));
    }
    platform.run().expect("the run");
    ticks.get()
}

fn percentile(sorted: &[f64], fraction: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * fraction).round() as usize]
}

/// Prints the bridge's cost per tick and its loopback round trip.
pub(crate) fn measure() {
    let ticks = run(None);
    let [bare, bridged] = mean_times(|variant| match variant {
        0 => run(None),
        _ => run(Some("tcp/127.0.0.1:7451")),
    });
    let per_tick = |time: Duration| time.as_secs_f64() / ticks as f64;
    println!("PickAndPlaceWorld idle, {SECONDS} s of platform time ({ticks} ticks), side by side:");
    println!(
        "  without the bridge  {:>8.0} ticks/s",
        1.0 / per_tick(bare)
    );
    println!(
        "  with the bridge     {:>8.0} ticks/s  ({:.2} µs more a tick; states at 50 Hz)",
        1.0 / per_tick(bridged),
        (per_tick(bridged) - per_tick(bare)) * 1e6
    );

    let endpoint = "tcp/127.0.0.1:7452";
    let world = PlatformThread::spawn(move || {
        yarok::platform()
            .world::<PickAndPlaceWorld>()
            .plugin(bridge(endpoint))
            .behaviour(|pl| async move {
                pl.wait_forever().await?;
                Ok(())
            })
    });
    let mut config = zenoh::Config::default();
    config.insert_json5("mode", "\"client\"").unwrap();
    config
        .insert_json5("connect/endpoints", &format!("[{endpoint:?}]"))
        .unwrap();
    config
        .insert_json5("scouting/multicast/enabled", "false")
        .unwrap();
    let session = (0..100)
        .find_map(|_| {
            std::thread::sleep(Duration::from_millis(100));
            zenoh::open(config.clone()).wait().ok()
        })
        .expect("the world's bridge");
    let (pongs, received) = mpsc::channel();
    let _replies = session
        .declare_subscriber("yarok/world/reply")
        .callback(move |_| {
            let _ = pongs.send(Instant::now());
        })
        .wait()
        .unwrap();
    let publisher = session
        .declare_publisher("yarok/world/command")
        .wait()
        .unwrap();
    let mut round_trips = Vec::with_capacity(PINGS);
    for ping in 0..PINGS + 100 {
        let sent = Instant::now();
        publisher
            .put(format!("{{\"ping\": {ping}}}"))
            .wait()
            .unwrap();
        let answered = received
            .recv_timeout(Duration::from_secs(5))
            .expect("a pong");
        if ping >= 100 {
            round_trips.push((answered - sent).as_secs_f64() * 1e6);
        }
    }
    round_trips.sort_by(f64::total_cmp);
    println!(
        "ping to the world's bridge and back on loopback ({PINGS}): p50 {:.0} µs, p99 {:.0} µs, \
         max {:.0} µs",
        percentile(&round_trips, 0.5),
        percentile(&round_trips, 0.99),
        round_trips[round_trips.len() - 1]
    );
    world.stop();
    world.join().expect("the world ends");
}
