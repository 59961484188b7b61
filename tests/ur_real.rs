//! The UR arms with `--env real`, against the project's fake controller driving a simulated UR5e
//! (or UR5) in real time: joint and linear moves sent as URScript arrive (joints read over RTDE); a
//! UR5 configured on a UR5e is refused, naming both; a protective stop mid-move fails the motion
//! saying so, and after unlocking it the arm moves again; dropped RTDE and secondary connections
//! are reconnected while the behaviour waits; a CB3 UR5 moves too and takes its payload; dropping a
//! motion's future stops the arm; the arm is stopped when the run ends; a controller in local
//! control, an arm powered off or in a protective stop, is refused at connect in words; an arm powered off mid-motion
//! fails the motion at once; a motion lost to a controller restart is named so; an RTDE service
//! that answers but sends no data is named, without a tight loop of reconnections.

use std::time::Duration;

use yarok::Component;
use yarok::components::robots::ur::{MotionError, Ur5, Ur5e, pose_from_vector, pose_to_vector};

mod support;
use support::simulated_ur;
use yarok_test::ur_controller;

use simulated_ur::{SimulatedArm, Ur5Alone, Ur5eAlone};
use ur_controller::{FakeController, Profile};
use yarok_test::assert_says;

/// Where the arms start.
const START: [f64; 6] = [0.0, -1.3, 1.2, -1.5, -1.57, 0.0];

/// A fake e-Series controller with a simulated UR5e.
fn fake_ur5e() -> FakeController {
    FakeController::with_arm(Profile::ESeries, SimulatedArm::ur5e(START))
}

fn real<W: Component>(fake: &FakeController) -> yarok::core::runtime::PlatformBuilder {
    yarok::platform()
        .world::<W>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/arm/host=\"{}\"", fake.host),
            // Any free port for the streaming program: tests run side by side.
            "--set".to_owned(),
            "interfaces/arm/reverse_port=0".to_owned(),
        ])
        .unwrap()
}

#[test]
fn joint_and_linear_moves_arrive() {
    let fake = fake_ur5e();
    real::<Ur5eAlone>(&fake)
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            assert!(arm.is_at(&START), "{:?}", arm.q());
            let q = [0.3, -1.2, 1.1, -1.4, -1.57, 0.2];
            arm.move_j(q).speed(2.0).acceleration(4.0).await?;
            assert!(arm.is_at(&q), "{:?}", arm.q());
            let mut pose = pose_to_vector(&arm.tcp_pose());
            pose[2] += 0.05;
            arm.move_l_vector(pose).await?;
            assert!(
                arm.is_at_pose(&pose_from_vector(pose)),
                "{:?}",
                arm.tcp_pose()
            );
            Ok(())
        })
        .run()
        .unwrap();
    // The stop goes out as the run ends; the fake may read it a moment later.
    let stopped = |scripts: &[String]| scripts.last().is_some_and(|last| last == "stopj(2.0)");
    let asked = std::time::Instant::now();
    while !stopped(&fake.scripts()) && asked.elapsed() < Duration::from_secs(2) {
        std::thread::sleep(Duration::from_millis(10));
    }
    let scripts = fake.scripts();
    assert!(stopped(&scripts), "stopped at the end: {scripts:?}");
    assert!(
        scripts.iter().any(|s| s.starts_with("movej([0.300000")),
        "{scripts:?}"
    );
    assert!(
        scripts.iter().any(|s| s.trim().starts_with("movel(p[")),
        "{scripts:?}"
    );
}

#[test]
fn a_ur5_configured_on_a_ur5e_is_refused_naming_both() {
    let fake = fake_ur5e();
    let error = real::<Ur5Alone>(&fake)
        .behaviour(|_| async { Ok(()) })
        .run()
        .unwrap_err()
        .to_string();
    assert_says(&error, &["/arm", "a UR5e (d1 0.1625", "a UR5 (d1 0.0892"]);
}

#[test]
fn a_protective_stop_fails_the_motion_and_unlocking_recovers() {
    let fake = fake_ur5e();
    std::thread::scope(|scope| {
        scope.spawn(|| {
            while fake.scripts().is_empty() {
                std::thread::sleep(Duration::from_millis(10));
            }
            std::thread::sleep(Duration::from_millis(200));
            // Long enough ago that the dashboard lets it be unlocked.
            fake.protective_stop(Duration::from_secs(6));
        });
        real::<Ur5eAlone>(&fake)
            .behaviour(|pl| async move {
                let arm: Ur5e = pl.get("/arm")?;
                let far = [1.5, -1.3, 1.2, -1.5, -1.57, 0.0];
                let stopped = arm.move_j(far).speed(0.5).await.unwrap_err();
                assert_eq!(
                    stopped,
                    MotionError::SafetyStop {
                        mode: "PROTECTIVE_STOP"
                    }
                );
                arm.unlock_protective_stop().await?;
                arm.move_j(far).speed(3.0).acceleration(6.0).await?;
                assert!(arm.is_at(&far));
                Ok(())
            })
            .run()
            .unwrap();
    });
}

#[test]
fn dropped_connections_are_reconnected_while_the_behaviour_waits() {
    let fake = fake_ur5e();
    std::thread::scope(|scope| {
        scope.spawn(|| {
            while fake.scripts().is_empty() {
                std::thread::sleep(Duration::from_millis(10));
            }
            std::thread::sleep(Duration::from_millis(100));
            fake.drop_streams();
        });
        real::<Ur5eAlone>(&fake)
            .behaviour(|pl| async move {
                let arm: Ur5e = pl.get("/arm")?;
                let q = [0.8, -1.3, 1.2, -1.5, -1.57, 0.0];
                arm.move_j(q).speed(1.0).await?;
                assert!(arm.is_at(&q));
                // The script goes over the new secondary connection.
                let back = [0.6, -1.3, 1.2, -1.5, -1.57, 0.0];
                arm.move_j(back).speed(2.0).await?;
                assert!(arm.is_at(&back));
                Ok(())
            })
            .run()
            .unwrap();
    });
    let asked = fake.asked();
    assert!(asked.len() >= 6, "the recipe was set up twice: {asked:?}");
}

#[test]
fn a_cb3_ur5_moves_and_takes_its_payload() {
    let fake = FakeController::with_arm(Profile::Cb3, SimulatedArm::ur5(START));
    yarok::platform()
        .world::<Ur5Alone>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/arm/host=\"{}\"", fake.host),
            "--set".to_owned(),
            "interfaces/arm/payload=[1.2, 0.0, 0.0, 0.05]".to_owned(),
        ])
        .unwrap()
        .behaviour(|pl| async move {
            let arm: Ur5 = pl.get("/arm")?;
            let q = [-0.4, -1.4, 1.3, -1.5, -1.57, 0.1];
            arm.move_j(q).speed(2.0).acceleration(4.0).await?;
            assert!(arm.is_at(&q), "{:?}", arm.q());
            // A grasped object changes it while running.
            arm.set_payload(2.5, [0.0, 0.01, 0.1])?;
            arm.move_j(START).speed(2.0).acceleration(4.0).await?;
            Ok(())
        })
        .run()
        .unwrap();
    let scripts = fake.scripts();
    assert_eq!(
        scripts.first().map(String::as_str),
        Some("set_payload(1.2, [0, 0, 0.05])")
    );
    assert!(
        scripts.contains(&"set_payload(2.5, [0, 0.01, 0.1])".to_owned()),
        "{scripts:?}"
    );
}

#[test]
fn motions_take_the_simulated_arms_time_and_speed() {
    let fake = fake_ur5e();
    real::<Ur5eAlone>(&fake)
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let mut q = START;
            q[0] += 0.6;
            let started = pl.time();
            let mut fastest = 0.0f64;
            let moving = async {
                arm.move_j(q).speed(0.5).acceleration(1.0).await?;
                Ok::<_, MotionError>(())
            };
            let watching = pl.wait(|| {
                fastest = fastest.max(arm.qd()[0].abs());
                false
            });
            tokio::select! {
                moved = moving => moved?,
                _ = watching => {}
            }
            // 0.6 rad at 0.5 rad/s, half a second to speed up and half to brake: 1.7 s.
            let took = pl.time() - started;
            assert!((1.65..2.2).contains(&took), "{took} s");
            assert!((0.48..0.51).contains(&fastest), "{fastest} rad/s");
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn dropping_a_motion_stops_the_arm() {
    let fake = fake_ur5e();
    real::<Ur5eAlone>(&fake)
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let far = [1.5, -1.3, 1.2, -1.5, -1.57, 0.0];
            let cut = pl
                .timeout(0.3, arm.move_j(far).speed(1.0).acceleration(4.0))
                .await;
            assert!(cut.is_err(), "the motion was still under way");
            pl.wait_seconds(0.3).await?;
            let stopped = arm.q()[0];
            assert!(stopped > 0.1 && stopped < 1.0, "{stopped}");
            pl.wait_seconds(0.3).await?;
            assert!((arm.q()[0] - stopped).abs() < 1e-3, "it stays stopped");
            Ok(())
        })
        .run()
        .unwrap();
    let scripts = fake.scripts();
    assert!(
        scripts
            .iter()
            .any(|s| s.starts_with("stopj(") && s != "stopj(2.0)"),
        "{scripts:?}"
    );
}

/// The secondary interface falls silent while RTDE streams (a hung controller service): the run
/// ends with an error naming the secondary interface instead of carrying on blind, and the
/// stop still reaches the controller over a fresh connection that waits for no robot state.
#[test]
fn a_silent_secondary_interface_ends_the_run_and_the_arm_is_still_stopped() {
    let fake = std::sync::Arc::new(fake_ur5e());
    let muting = std::sync::Arc::clone(&fake);
    let error = real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let _arm: Ur5e = pl.get("/arm")?;
            muting.mute_secondary();
            pl.wait_seconds(30.0).await?;
            Ok(())
        })
        .run()
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("secondary interface") || error.contains("robot state"),
        "{error}"
    );
    let stopped = |scripts: &[String]| scripts.iter().any(|s| s == "stopj(2.0)");
    let asked = std::time::Instant::now();
    while !stopped(&fake.scripts()) && asked.elapsed() < Duration::from_secs(2) {
        std::thread::sleep(Duration::from_millis(10));
    }
    assert!(stopped(&fake.scripts()), "no stopj: {:?}", fake.scripts());
}

#[test]
fn a_controller_in_local_control_powered_off_or_stopped_is_refused_in_words() {
    let local = fake_ur5e();
    local.set_remote_control(false);
    let error = real::<Ur5eAlone>(&local).run().unwrap_err().to_string();
    assert_says(&error, &["/arm", "local control", "remote"]);

    let off = fake_ur5e();
    off.power_off();
    let error = real::<Ur5eAlone>(&off).run().unwrap_err().to_string();
    assert_says(&error, &["/arm", "powered off"]);
    assert!(off.scripts().iter().all(|s| !s.starts_with("move")));

    let stopped = fake_ur5e();
    stopped.protective_stop(Duration::from_secs(1));
    let error = real::<Ur5eAlone>(&stopped).run().unwrap_err().to_string();
    assert_says(&error, &["safety system holds it (PROTECTIVE_STOP)"]);
}

/// Powered off during a 2-second motion, the arm's motion fails at once, naming the mode,
/// instead of "did not reach" after the motion's whole time.
#[test]
fn an_arm_powered_off_mid_motion_fails_the_motion_at_once() {
    let fake = std::sync::Arc::new(fake_ur5e());
    let switching = std::sync::Arc::clone(&fake);
    real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let far = [1.5, -1.3, 1.2, -1.5, -1.57, 0.0];
            let moving = arm.move_j(far).speed(0.75);
            let started = std::time::Instant::now();
            let (failed, ()) = tokio::join!(moving, async {
                pl.wait_seconds(0.3).await.unwrap();
                switching.power_off();
            });
            assert_eq!(failed, Err(MotionError::NotRunning { mode: "POWER_OFF" }));
            assert!(
                started.elapsed() < Duration::from_secs(1),
                "{:?}",
                started.elapsed()
            );
            Ok(())
        })
        .run()
        .unwrap();
}

/// The controller restarts during a motion (its program stops, its connections drop): the
/// motion ends saying its connection dropped and the controller did not finish it — not "did
/// not reach" as if something blocked the arm — and the next motion arrives.
#[test]
fn a_motion_lost_to_a_controller_restart_is_named_so() {
    let fake = std::sync::Arc::new(fake_ur5e());
    let restarting = std::sync::Arc::clone(&fake);
    real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let far = [1.5, -1.3, 1.2, -1.5, -1.57, 0.0];
            let (lost, ()) = tokio::join!(arm.move_j(far).speed(0.75), async {
                pl.wait_seconds(0.5).await.unwrap();
                restarting.restart();
            });
            let error = lost.unwrap_err();
            assert!(
                matches!(error, MotionError::ConnectionLost { .. }),
                "{error}"
            );
            assert_says(
                &error,
                &["dropped during the motion", "restarted", "move it again"],
            );
            arm.move_j(START).speed(1.0).await?;
            assert!(arm.is_at(&START));
            Ok(())
        })
        .run()
        .unwrap();
}

/// RTDE answers its requests but sends no data package: the run ends within a few reply times
/// with an error naming RTDE as mute (not a motion "not reached" on stale joints), reconnecting
/// it a few times with growing waits rather than in a tight loop, and the arm is stopped.
#[test]
fn a_mute_rtde_is_named_without_a_tight_loop_of_reconnections() {
    let fake = std::sync::Arc::new(fake_ur5e());
    let muting = std::sync::Arc::clone(&fake);
    let started = std::time::Instant::now();
    let error = real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            muting.mute_rtde(true);
            arm.move_j([0.2, -1.3, 1.2, -1.5, -1.57, 0.0])
                .speed(2.0)
                .await?;
            pl.wait_seconds(30.0).await?;
            Ok(())
        })
        .run()
        .unwrap_err()
        .to_string();
    let took = started.elapsed();
    assert_says(&error, &["RTDE", "mute"]);
    assert!(!error.contains("did not reach"), "{error}");
    assert!(took < Duration::from_secs(10), "{took:?}");
    // Waits doubling from 0.1 s within the 2 s reply time leave room for five attempts.
    let reconnections = fake.rtde_connections() - 1;
    assert!(
        (1..=5).contains(&reconnections),
        "{reconnections} reconnections"
    );
    println!("{error}\n{reconnections} reconnections, ended after {took:?}");
    let stopped = |scripts: &[String]| scripts.iter().any(|s| s == "stopj(2.0)");
    let asked = std::time::Instant::now();
    while !stopped(&fake.scripts()) && asked.elapsed() < Duration::from_secs(2) {
        std::thread::sleep(Duration::from_millis(10));
    }
    assert!(stopped(&fake.scripts()), "no stopj: {:?}", fake.scripts());
}

/// Connecting that runs out of `connect_seconds` names the controller's address, the step it
/// was at and the setting (here the secondary interface accepts but sends no robot state).
#[test]
fn a_connection_that_runs_out_of_time_names_the_address_the_step_and_the_setting() {
    let fake = fake_ur5e();
    fake.mute_secondary();
    let error = yarok::platform()
        .world::<Ur5eAlone>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/arm/host=\"{}\"", fake.host),
            "--set".to_owned(),
            "interfaces/arm/connect_seconds=0.5".to_owned(),
        ])
        .unwrap()
        .behaviour(|_| async { panic!("the arm connected") })
        .run()
        .unwrap_err()
        .to_string();
    assert_says(
        &error,
        &[
            &format!(
                "controller {}: connecting did not finish within 0.5 s",
                fake.host
            ),
            "(the interface setting connect_seconds)",
            "it was opening its secondary interface (port 30002) and reading a robot state",
        ],
    );
}

/// A controller whose secondary interface sends no robot state is named once, not twice
/// ("controller X: controller X: …").
#[test]
fn a_silent_controller_is_named_once() {
    let fake = fake_ur5e();
    fake.mute_secondary();
    let error = real::<Ur5eAlone>(&fake)
        .behaviour(|_| async { panic!("the arm connected") })
        .run()
        .unwrap_err()
        .to_string();
    let named = format!("controller {}", fake.host);
    assert_eq!(error.matches(&named).count(), 1, "{error}");
    assert_says(&error, &["no robot state within"]);
}

/// The controller switched to local control while a behaviour runs (it would ignore the
/// scripts sent to it): the next motion ends the run naming it, not with a position miss.
#[test]
fn a_controller_switched_to_local_control_mid_run_is_named() {
    let fake = std::sync::Arc::new(fake_ur5e());
    let switching = std::sync::Arc::clone(&fake);
    let error = real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            switching.set_remote_control(false);
            pl.wait_seconds(1.5).await?;
            arm.move_j([0.2, -1.3, 1.2, -1.5, -1.57, 0.0])
                .speed(2.0)
                .await?;
            pl.wait_seconds(5.0).await?;
            Ok(())
        })
        .run()
        .unwrap_err()
        .to_string();
    assert_says(
        &error,
        &[
            &format!(
                "controller {} was switched to local control while running",
                fake.host
            ),
            "switch it back to remote control on the teach pendant",
        ],
    );
    assert!(!error.contains("did not reach"), "{error}");
}

/// The fastest any joint was asked to turn by the targets the streaming programs read, each
/// from the one before (the first from `start`) over its period, rad/s; and how many there
/// were.
fn fastest_asked(fake: &FakeController, start: [f64; 6]) -> (f64, usize) {
    let mut before = start;
    let mut fastest: f64 = 0.0;
    let targets = fake.program_targets();
    for (_, joints, period) in &targets {
        let far = (0..6)
            .map(|i| (joints[i] - before[i]).abs())
            .fold(0.0, f64::max);
        fastest = fastest.max(far / period);
        before = *joints;
    }
    (fastest, targets.len())
}

/// A policy's target 3 rad from where the arm is, streamed at 20 Hz: one streaming program
/// runs for the whole stream; the arm is never asked beyond its joints' 180°/s (each target
/// is where the approach at the limits is due), and arrives.
#[test]
fn a_streamed_jump_is_approached_within_the_joint_speed_limit() {
    let fake = fake_ur5e();
    let target = [3.0, -1.3, 1.2, -1.5, -1.57, 0.0];
    real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            for _ in 0..50 {
                arm.servo_j(target, 0.05)?;
                pl.wait_seconds(0.05).await?;
            }
            assert!(
                (arm.q()[0] - target[0]).abs() < 0.01,
                "the arm is at {:?}",
                arm.q()
            );
            Ok(())
        })
        .run()
        .unwrap();
    let (fastest, count) = fastest_asked(&fake, START);
    assert!(count >= 45, "{count} targets sent");
    let programs = fake.scripts();
    let programs: Vec<&String> = programs
        .iter()
        .filter(|s| s.starts_with("def yarok_stream():"))
        .collect();
    assert_eq!(programs.len(), 1, "one program for the stream");
    let limit = yarok::components::robots::ur::UR_JOINT_SPEED;
    assert!(fastest <= limit + 1e-3, "a target asked {fastest} rad/s");
    assert!(
        fastest > 0.9 * limit,
        "the approach went at the limit: {fastest} rad/s"
    );
}

/// A dashboard that answers 0.3 s late (the once-a-second remote-control check) delays no
/// target of a 20 Hz stream: none reaches the streaming program more than 0.15 s after the one
/// before, and none in a burst.
#[test]
fn a_late_dashboard_does_not_stall_the_stream() {
    let fake = fake_ur5e();
    fake.set_dashboard_delay(Duration::from_millis(300));
    real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            for step in 0..60 {
                let mut target = START;
                target[0] += 0.005 * f64::from(step);
                arm.servo_j(target, 0.05)?;
                pl.wait_seconds(0.05).await?;
            }
            Ok(())
        })
        .run()
        .unwrap();
    let arrivals: Vec<std::time::Instant> = fake
        .program_targets()
        .into_iter()
        .map(|(arrived, _, _)| arrived)
        .collect();
    assert!(arrivals.len() >= 55, "{} targets arrived", arrivals.len());
    // From the second on: the behaviour's first wait may end early, as the platform's clock
    // catches up with connecting.
    let gaps: Vec<f64> = arrivals[1..]
        .windows(2)
        .map(|pair| (pair[1] - pair[0]).as_secs_f64())
        .collect();
    let longest = gaps.iter().copied().fold(0.0, f64::max);
    let shortest = gaps.iter().copied().fold(f64::MAX, f64::min);
    assert!(longest < 0.15, "the stream stalled {longest} s");
    assert!(shortest > 0.01, "a burst: two targets {shortest} s apart");
}

/// A protective stop while a policy streams at 20 Hz: the streaming program ends, the next
/// target is refused naming the stop, within 0.5 s of it; no target goes out from then on, not
/// even once the stop is unlocked, until the stream is re-armed — and then a new program
/// starts from where the arm is.
#[test]
fn a_protective_stop_ends_a_stream_until_it_is_rearmed() {
    use std::sync::{Arc, Mutex};
    use std::time::Instant;

    let fake = Arc::new(fake_ur5e());
    let stopping = Arc::clone(&fake);
    // When the stop happened, when a target was first refused, when the stream was re-armed
    // and where the arm was then.
    let times: Arc<Mutex<[Option<Instant>; 3]>> = Arc::default();
    let rearmed_at = Arc::new(Mutex::new(START));
    let (recorded, at) = (Arc::clone(&times), Arc::clone(&rearmed_at));
    real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let mut target = START;
            for step in 0..40 {
                if step == 10 {
                    // Long enough ago that the dashboard lets it be unlocked.
                    stopping.protective_stop(Duration::from_secs(6));
                    recorded.lock().unwrap()[0] = Some(Instant::now());
                }
                target[0] += 0.005;
                match arm.servo_j(target, 0.05) {
                    Ok(()) => assert!(recorded.lock().unwrap()[1].is_none(), "streamed again"),
                    Err(error) => {
                        assert!(error.to_string().contains("PROTECTIVE_STOP"), "{error}");
                        recorded.lock().unwrap()[1].get_or_insert(Instant::now());
                    }
                }
                if step == 25 {
                    arm.unlock_protective_stop().await?;
                    let after = arm.servo_j(target, 0.05).unwrap_err();
                    assert!(
                        matches!(after, MotionError::StreamStopped { .. }),
                        "{after}"
                    );
                }
                pl.wait_seconds(0.05).await?;
            }
            arm.rearm();
            recorded.lock().unwrap()[2] = Some(Instant::now());
            *at.lock().unwrap() = arm.q();
            arm.servo_j(arm.q(), 0.05)?;
            pl.wait_seconds(0.2).await?;
            Ok(())
        })
        .run()
        .unwrap();
    let [Some(stopped), Some(refused), Some(rearmed)] = *times.lock().unwrap() else {
        panic!("{:?}", times.lock().unwrap());
    };
    assert!(
        refused - stopped < Duration::from_millis(500),
        "{:?}",
        refused - stopped
    );
    let targets = fake.program_targets();
    let quiet = refused + Duration::from_millis(20)..rearmed;
    let meanwhile = targets
        .iter()
        .filter(|(arrived, _, _)| quiet.contains(arrived))
        .count();
    assert_eq!(meanwhile, 0, "targets sent while the stream was stopped");
    let (_, resumed, _) = targets.last().unwrap();
    let held = *rearmed_at.lock().unwrap();
    assert!(
        (0..6).all(|i| (resumed[i] - held[i]).abs() < 1e-3),
        "{resumed:?} from {held:?}"
    );
    let ends = fake.program_ends();
    assert!(
        ends.first()
            .is_some_and(|(at, why)| why.contains("PROTECTIVE_STOP") && *at < refused),
        "{ends:?}"
    );
    assert_eq!(fake.programs_started(), 2, "a new program after re-arming");
}

/// yarok falls silent mid-stream (its thread blocked 0.6 s, as a hung process or a cut
/// network would): the streaming program's watchdog stops the arm within its time (0.2 s, and
/// a controller step); the next target is refused naming the program's end, until the stream
/// is re-armed, when a new program streams again.
#[test]
fn a_silent_sender_is_stopped_by_the_programs_watchdog() {
    use std::sync::{Arc, Mutex};
    use std::time::Instant;

    let fake = fake_ur5e();
    let silent_from: Arc<Mutex<Option<Instant>>> = Arc::default();
    let noted = Arc::clone(&silent_from);
    let refused: Arc<Mutex<Option<Result<(), MotionError>>>> = Arc::default();
    let refusal = Arc::clone(&refused);
    real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let mut target = START;
            for _ in 0..10 {
                target[0] += 0.01;
                arm.servo_j(target, 0.05)?;
                pl.wait_seconds(0.05).await?;
            }
            *noted.lock().unwrap() = Some(Instant::now());
            std::thread::sleep(Duration::from_millis(600));
            // The platform's clock catches up at once after a block: wait in wall time.
            let woke = Instant::now();
            while woke.elapsed() < Duration::from_millis(150) {
                pl.wait_seconds(0.01).await?;
            }
            *refusal.lock().unwrap() = Some(arm.servo_j(target, 0.05));
            arm.rearm();
            arm.servo_j(arm.q(), 0.05)?;
            pl.wait_seconds(0.3).await?;
            Ok(())
        })
        .run()
        .unwrap();
    let silent_from = silent_from.lock().unwrap().unwrap();
    let ends = fake.program_ends();
    match refused.lock().unwrap().take() {
        // Refused as the program's end, or as the stream that end stopped.
        Some(Err(MotionError::StreamStopped { cause }))
            if matches!(*cause, MotionError::ProgramStopped { .. }) =>
        {
            assert!(cause.to_string().contains("watchdog"), "{cause}")
        }
        Some(Err(error @ MotionError::ProgramStopped { .. })) => {
            assert!(error.to_string().contains("watchdog"), "{error}")
        }
        other => panic!("{other:?} after the program ended: {ends:?}"),
    }
    let (ended_at, why) = ends.first().expect("the program ended");
    assert!(why.contains("watchdog"), "{why}");
    let late = ended_at.duration_since(silent_from).as_secs_f64();
    assert!(
        late < 0.2 + 0.05,
        "the watchdog stopped the arm {late} s after the last word"
    );
    let steps_after = fake
        .program_steps()
        .iter()
        .filter(|(at, _)| at > ended_at && *at < silent_from + Duration::from_millis(600))
        .count();
    assert_eq!(steps_after, 0, "the stopped program moved the arm");
    assert_eq!(fake.programs_started(), 2, "a new program after re-arming");
}

/// A behaviour that streams at 20 Hz, pauses 2 s (a model warming up), streams at 20 Hz again,
/// then at 12.5 Hz: one streaming program throughout (kept alive through the pause), no target
/// asks beyond the joint speed limit, none comes in a burst, and the arm follows.
#[test]
fn a_paused_then_slower_stream_keeps_one_program_within_the_limits() {
    let fake = fake_ur5e();
    real::<Ur5eAlone>(&fake)
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let mut target = START;
            for step in 0..40 {
                if step == 10 {
                    pl.wait_seconds(2.0).await?;
                }
                let period = if step >= 25 { 0.08 } else { 0.05 };
                target[0] += 0.02;
                arm.servo_j(target, period)?;
                pl.wait_seconds(period).await?;
            }
            pl.wait_seconds(0.3).await?;
            assert!(
                (arm.q()[0] - target[0]).abs() < 0.01,
                "the arm is at {:?}",
                arm.q()
            );
            Ok(())
        })
        .run()
        .unwrap();
    let (fastest, count) = fastest_asked(&fake, START);
    assert_eq!(count, 40, "one target per step");
    let limit = yarok::components::robots::ur::UR_JOINT_SPEED;
    assert!(fastest <= limit + 1e-3, "a target asked {fastest} rad/s");
    let arrivals: Vec<std::time::Instant> = fake
        .program_targets()
        .into_iter()
        .map(|(arrived, _, _)| arrived)
        .collect();
    let shortest = arrivals
        .windows(2)
        .map(|pair| (pair[1] - pair[0]).as_secs_f64())
        .fold(f64::MAX, f64::min);
    assert!(shortest > 0.01, "a burst: two targets {shortest} s apart");
    let ends = fake.program_ends();
    let before_the_end: Vec<_> = ends
        .iter()
        .filter(|(at, _)| *at < *arrivals.last().unwrap())
        .collect();
    assert!(before_the_end.is_empty(), "{ends:?}");
}
