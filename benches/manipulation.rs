//! Measures, side by side in one run, for manipulation: a UR5e inverse kinematics solve (every
//! solution, then the nearest within the limits; target ≤ 2 µs), the platform loop in
//! `PickAndPlaceWorld` against raw `mj_step` on the same model from the same state (target
//! ≥ 95 %), and the world's start-up: compose, compile, bind and the first tick.
//!
//! ```text
//! cargo bench --bench manipulation
//! ```

use std::f64::consts::{PI, TAU};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use yarok::components::robots::ur::{DhParameters, Joints, Kinematics};
use yarok::components::tactile::noise::SplitMix64;
use yarok::components::worlds::PickAndPlaceWorld;
use yarok::core::compose::compose;
use yarok::mjc::Data;

mod measure;
mod versus_raw;
use measure::mean_times;
use versus_raw::compare;

/// The arm's joints as `PickAndPlaceWorld` starts them (its `/arm` config), read once.
fn start() -> Joints {
    static START: OnceLock<Joints> = OnceLock::new();
    *START.get_or_init(|| {
        let composition = compose::<PickAndPlaceWorld>().expect("compose");
        let arm = composition.instance("/arm").expect("the world's arm");
        arm.config
            .get("start")
            .expect("the arm's start")
            .deserialize()
            .expect("six joint angles")
    })
}

/// The arm placed and held where the platform starts it, for raw stepping from the same state.
fn arm_at_start(data: &mut Data) {
    let model = std::sync::Arc::clone(data.model());
    for (name, angle) in yarok::components::robots::ur::ArmNames::YAROK
        .joints
        .iter()
        .zip(start())
    {
        let joint = model.joint(&format!("arm/{name}")).expect("joint");
        data.qpos_mut(joint)[0] = angle;
        let servo = model.actuator(&format!("arm/{name}")).expect("servo");
        data.set_ctrl(servo, angle);
    }
}

/// Mean time of one IK solve over poses of random joint angles.
fn ik_solve() -> Duration {
    let kinematics = Kinematics::new(DhParameters::UR5E);
    let mut random = SplitMix64::new(1);
    let mut angle = |limit: f64| random.uniform(-limit, limit);
    let cases: Vec<_> = (0..4096)
        .map(|_| {
            let q: Joints = std::array::from_fn(|i| angle(if i == 2 { PI } else { TAU }));
            (kinematics.forward(&q), q.map(|a| a + 0.05))
        })
        .collect();
    let mut next = 0;
    let [time] = mean_times(|_| {
        let (pose, near) = &cases[next % cases.len()];
        next += 1;
        kinematics.nearest(pose, near).ok()
    });
    time
}

/// Milliseconds from nothing to the first tick: compose, compile, bind, one step.
fn start_up() -> f64 {
    let runs = 20;
    let mut total = 0.0;
    for _ in 0..runs {
        let started = Instant::now();
        let elapsed = std::rc::Rc::new(std::cell::Cell::new(0.0));
        let out = std::rc::Rc::clone(&elapsed);
        yarok::platform()
            .world::<PickAndPlaceWorld>()
            .behaviour(move |pl| async move {
                pl.tick().await?;
                out.set(started.elapsed().as_secs_f64());
                Ok(())
            })
            .run()
            .expect("run");
        total += elapsed.get();
    }
    total / runs as f64 * 1e3
}

fn main() {
    let ik = ik_solve();
    println!(
        "UR5e inverse kinematics      {:>8.2} µs per solve (target ≤ 2)",
        ik.as_secs_f64() * 1e6
    );
    let measured = compare::<PickAndPlaceWorld>(1, arm_at_start);
    println!(
        "PickAndPlaceWorld            {:>8.0} raw steps/s, platform {:.0} ({:.1} %, {:.2} µs a tick, median {:.1} %; {} rounds × {} steps; target ≥ 95 %)",
        measured.raw,
        measured.platform,
        100.0 * measured.ratio(),
        measured.overhead_us(),
        100.0 * measured.median_ratio,
        measured.rounds,
        measured.ticks,
    );
    println!(
        "start-up to the first tick   {:>8.1} ms (compose, compile, bind, one step)",
        start_up()
    );
}
