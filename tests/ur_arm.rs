//! The UR arms in MuJoCo: the model's flange is the kinematics' tool0, the servos hold a pose
//! under gravity, `move_j` keeps to its speed and acceleration, `move_l` keeps the TCP on its
//! line, runs repeat bit for bit, bad targets fail before anything moves, a dropped motion
//! stops the arm, and `mock` follows its motions. (MuJoCo Menagerie's UR5e: `tests/third_party_robots.rs`.)

use std::cell::RefCell;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::rc::Rc;
use std::sync::Arc;

use yarok::components::robots::ur::{
    Arm, ArmNames, DhParameters, Joints, MOVE_J_DEFAULTS, MOVE_L_DEFAULTS, MotionError, Ur5, Ur5e,
    isometry_of, pose_from_vector,
};
use yarok::components::tactile::noise::SplitMix64;
use yarok::components::worlds::EmptyWorld;
use yarok::core::compose::compose;
use yarok::mjc::{Data, Model};
use yarok::nalgebra::{Isometry3, Translation3, Vector3};
use yarok::prelude::*;

const HOME: Joints = [0.0, -FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2, 0.0];

/// An empty world with an arm `A` at `/arm` on the floor.
struct ArmWorld<A>(std::marker::PhantomData<A>);

impl<A: Component> Component for ArmWorld<A> {
    fn declaration() -> Declaration {
        let tag = A::declaration().tag().to_owned();
        Declaration::new(format!("{tag}_world"))
            .extends::<EmptyWorld>()
            .uses::<A>()
            .template(format!(
                r#"<mujoco><worldbody><{tag} name="arm" pos="0 0 0.05"/></worldbody></mujoco>"#
            ))
    }
}

#[test]
fn the_flange_site_is_tool0_of_the_kinematics() {
    fn check<A: Component>(dh: DhParameters) {
        let model = Arc::new(Model::from_composition(&compose::<A>().unwrap()).unwrap());
        let mut data = Data::new(&model).unwrap();
        let names = ArmNames::YAROK.joints;
        let joints = names.map(|name| model.joint(name).unwrap());
        let flange = model.site("flange").unwrap();
        let mut random = SplitMix64::new(5);
        for _ in 0..1000 {
            let q: Joints = std::array::from_fn(|i| {
                let limit = if i == 2 { PI } else { TAU };
                random.uniform(-limit, limit)
            });
            for (joint, angle) in joints.iter().zip(q) {
                data.qpos_mut(*joint)[0] = angle;
            }
            data.forward();
            let site = isometry_of(&data.site_pose(flange));
            let expected = dh.forward(&q);
            let position = (site.translation.vector - expected.translation.vector).norm();
            let angle = site.rotation.angle_to(&expected.rotation);
            assert!(
                position < 1e-6 && angle < 1e-6,
                "{dh:?} at {q:?}: {position} m, {angle} rad"
            );
        }
    }
    check::<Ur5e>(DhParameters::UR5E);
    check::<Ur5>(DhParameters::UR5);
}

/// Runs `behaviour` on an arm of type `A` in its world, in `sim`.
fn run<A, F>(behaviour: impl FnOnce(A, Pl) -> F + 'static) -> Result<(), yarok::RuntimeError>
where
    A: Component + Clone + std::ops::Deref<Target = Arm>,
    F: Future<Output = BehaviourResult> + 'static,
{
    yarok::platform()
        .world::<ArmWorld<A>>()
        .behaviour(move |pl| async move {
            let arm: A = pl.get("/arm")?;
            behaviour(arm, pl).await
        })
        .run()
}

#[test]
fn the_servos_hold_a_pose_under_gravity() {
    run(|arm: Ur5e, pl| async move {
        let target = [0.4, -1.0, 1.3, -1.9, -1.4, 0.6];
        arm.move_j(target).await?;
        let mut worst = 0.0f64;
        pl.wait_seconds(3.0)
            .on_tick(|| {
                let q = arm.q();
                worst = q
                    .iter()
                    .zip(target)
                    .map(|(a, b)| (a - b).abs())
                    .fold(worst, f64::max);
            })
            .await?;
        assert!(
            worst < 1e-3,
            "the arm drifts {worst} rad from the pose it holds"
        );
        Ok(())
    })
    .unwrap();
}

#[test]
fn move_j_keeps_to_its_speed_and_acceleration_and_arrives() {
    run(|arm: Ur5, pl| async move {
        let (speed, acceleration) = MOVE_J_DEFAULTS;
        let dt = pl.timestep();
        let trace = Rc::new(RefCell::new(Vec::new()));
        let recorder = Rc::clone(&trace);
        let watched = arm.clone();
        let watch = pl
            .wait_forever()
            .on_tick(move || recorder.borrow_mut().push(watched.qd()));
        let target = [1.2, -1.9, 2.0, -1.0, 0.5, -0.8];
        tokio::select! {
            biased;
            result = arm.move_j(target) => result?,
            _ = watch => {}
        }
        assert!(arm.is_at(&target));
        let trace = trace.borrow();
        let fastest = trace.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        // Accelerations over 10 ms: the servos' ripple averaged out (they overshoot the
        // profile's corners by 1 % here).
        let hardest = trace
            .windows(6)
            .flat_map(|w| (0..6).map(move |i| (w[5][i] - w[0][i]).abs() / (5.0 * dt)))
            .fold(0.0f64, f64::max);
        assert!(
            fastest <= speed * 1.02,
            "joint speed {fastest} rad/s over {speed}"
        );
        assert!(
            fastest > speed * 0.95,
            "the leading joint cruises at {fastest}, not {speed}"
        );
        assert!(
            hardest <= acceleration * 1.1,
            "joint acceleration {hardest} over {acceleration}"
        );
        Ok(())
    })
    .unwrap();
}

#[test]
fn move_l_keeps_the_tcp_on_its_line() {
    run(|arm: Ur5e, pl| async move {
        arm.move_j(HOME).await?;
        let start = arm.tcp_pose();
        let end = Isometry3::from_parts(
            Translation3::from(start.translation.vector + Vector3::new(0.25, -0.15, 0.1)),
            start.rotation,
        );
        let (a, b) = (start.translation.vector, end.translation.vector);
        let mut worst = 0.0f64;
        let mut positions = Vec::new();
        let watched = arm.clone();
        let watch = pl.wait_forever().on_tick(|| {
            let p = watched.tcp_pose().translation.vector;
            let along = ((p - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
            worst = worst.max((p - (a + along * (b - a))).norm());
            positions.push(p);
        });
        tokio::select! {
            biased;
            result = arm.move_l(end) => result?,
            _ = watch => {}
        }
        assert!(arm.is_at_pose(&end), "{:?} vs {end:?}", arm.tcp_pose());
        assert!(worst < 0.002, "the TCP leaves the line by {worst} m");
        // Speeds and accelerations over 10 ms: the servos' ripple averaged out.
        let (speed, acceleration) = MOVE_L_DEFAULTS;
        let dt = pl.timestep();
        let over_10_ms = |w: &[Vector3<f64>]| (w[5] - w[0]) / (5.0 * dt);
        let speeds: Vec<_> = positions.windows(6).map(over_10_ms).collect();
        let fastest = speeds.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let hardest = speeds
            .windows(6)
            .map(|w| over_10_ms(w).norm())
            .fold(0.0, f64::max);
        assert!(
            fastest < speed * 1.02 && fastest > speed * 0.95,
            "TCP speed {fastest} m/s"
        );
        // The servos overshoot the profile's corners a little (5 % over 10 ms here).
        assert!(
            hardest < acceleration * 1.1,
            "TCP acceleration {hardest} m/s²"
        );
        Ok(())
    })
    .unwrap();
}

#[test]
fn the_same_behaviour_gives_bit_identical_trajectories() {
    let trajectory = || {
        let trace = Rc::new(RefCell::new(Vec::new()));
        let recorder = Rc::clone(&trace);
        run(move |arm: Ur5e, pl| async move {
            let watched = arm.clone();
            let watch = pl
                .wait_forever()
                .on_tick(move || recorder.borrow_mut().push(watched.q()));
            tokio::select! {
                biased;
                result = async {
                    arm.move_j(HOME).await?;
                    arm.move_l_vector([-0.3, 0.3, 0.4, PI, 0.0, 0.0]).await
                } => result?,
                _ = watch => {}
            }
            Ok(())
        })
        .unwrap();
        Rc::try_unwrap(trace).unwrap().into_inner()
    };
    let (first, second) = (trajectory(), trajectory());
    assert!(first.len() > 100);
    assert!(first == second, "two runs differ");
}

#[test]
fn bad_targets_fail_before_anything_moves() {
    run(|arm: Ur5e, pl| async move {
        arm.move_j(HOME).await?;
        pl.wait_seconds(0.2).await?;
        let before = arm.q();
        let outside = [0.0, 0.0, 4.0, 0.0, 0.0, 0.0];
        let error = arm.move_j(outside).await.unwrap_err();
        assert!(
            matches!(error, MotionError::InvalidTarget { .. }),
            "{error}"
        );
        let nan = [f64::NAN; 6];
        assert!(arm.move_j(nan).start().is_err());
        let far = arm
            .move_l_vector([2.0, 0.0, 0.5, PI, 0.0, 0.0])
            .await
            .unwrap_err();
        assert!(far.to_string().contains("out of the arm's reach"), "{far}");
        let slow = arm.move_j(HOME).speed(0.0).await.unwrap_err();
        assert!(matches!(slow, MotionError::InvalidLimits { .. }), "{slow}");
        pl.wait_seconds(0.2).await?;
        assert!(!arm.is_moving());
        let moved = arm
            .q()
            .iter()
            .zip(before)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(moved < 1e-4, "the arm moved {moved} rad");
        Ok(())
    })
    .unwrap();
}

#[test]
fn a_dropped_motion_stops_the_arm_and_stop_ends_an_awaited_one() {
    run(|arm: Ur5e, pl| async move {
        let far = [2.5, -1.0, 1.0, -1.0, -1.0, 1.0];
        // Dropped by the timeout a third of a second in.
        let result = pl.timeout(0.3, arm.move_j(far)).await;
        assert!(result.is_err());
        pl.wait(|| !arm.is_moving()).timeout(2.0).await?;
        pl.wait_seconds(0.3).await?;
        let q = arm.q();
        assert!(!arm.is_at(&far) && q[0] > 0.05 && q[0] < 1.5, "{q:?}");
        assert!(arm.qd().iter().all(|v| v.abs() < 1e-2), "{:?}", arm.qd());
        // A stop from elsewhere ends an awaited motion with an error.
        let stopper = arm.clone();
        let (moved, ()) = tokio::join!(arm.move_j(HOME), async {
            let _ = pl.wait_seconds(0.2).await;
            stopper.stop();
        });
        assert!(matches!(moved, Err(MotionError::Stopped)), "{moved:?}");
        Ok(())
    })
    .unwrap();
}

#[test]
fn mock_arms_follow_their_motions() {
    yarok::platform()
        .world::<ArmWorld<Ur5e>>()
        .environment("mock")
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let started = pl.time();
            arm.move_j(HOME).await?;
            assert!(arm.is_at(&HOME));
            assert!(
                pl.time() - started > 1.0,
                "the motion takes its profile's time"
            );
            let target = pose_from_vector([-0.3, 0.35, 0.3, PI, 0.0, 0.0]);
            arm.move_l(target).await?;
            assert!(arm.is_at_pose(&target));
            Ok(())
        })
        .run()
        .unwrap();
}

/// A streamed target 2.5 rad away, given every 50 ms as a policy gives its actions: the arm
/// approaches it under gravity at its servo limits — the base turning no faster than 180°/s
/// and speeding up no faster than 360°/s² — and holds it.
#[test]
fn a_streamed_jump_is_approached_at_the_servo_limits_and_held() {
    yarok::platform()
        .world::<ArmWorld<Ur5e>>()
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let start = arm.q();
            let mut target = start;
            target[0] += 2.5;
            let limits = arm.servo_limits();
            let (mut fastest, mut hardest, mut before) = (0.0_f64, 0.0_f64, 0.0);
            for _ in 0..40 {
                arm.servo_j(target, 0.05)?;
                for _ in 0..25 {
                    pl.tick().await?;
                    let speed = arm.qd()[0];
                    fastest = fastest.max(speed.abs());
                    hardest = hardest.max(((speed - before) / pl.timestep()).abs());
                    before = speed;
                }
            }
            assert!((arm.q()[0] - target[0]).abs() < 2e-3, "{:?}", arm.q());
            // The servos track the setpoint closely; their own ripple adds a little.
            assert!(fastest <= limits.speed()[0] * 1.02, "{fastest} rad/s");
            assert!(fastest >= limits.speed()[0] * 0.95, "{fastest} rad/s");
            assert!(
                hardest <= limits.acceleration()[0] * 1.5,
                "{hardest} rad/s²"
            );
            Ok(())
        })
        .run()
        .unwrap();
}
