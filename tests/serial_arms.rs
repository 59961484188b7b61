//! Any serial arm, unmodified, driven with the UR arms' motions: robosuite's Franka Panda, KUKA
//! iiwa and Kinova Gen3 (7-DoF arms on torque motors, files from the installed `robosuite`
//! package, no gravity compensation in them) each make three `move_j` motions and a 20 cm
//! `move_l` under gravity: every motion arrives within 1e-3 rad, the TCP (MuJoCo's, not ours)
//! stays within 1 mm of the straight line, no joint ever leaves its limits, and two runs move
//! the arm identically, bit for bit. A target out of reach and a line through a singularity are
//! errors before anything moves.

use std::path::PathBuf;

use yarok::components::robots::serial::{
    DEFAULT_STIFFNESS, SerialArm, SerialMotionError, SerialNames,
};
use yarok::nalgebra::{Isometry3, Vector3};
use yarok::prelude::*;

use yarok_test::peers;

/// A robot file of robosuite's, from the installed package.
fn robosuite(robot: &str) -> PathBuf {
    peers::package("robosuite")
        .join("models/assets/robots")
        .join(robot)
        .join("robot.xml")
}

/// A robosuite arm wrapped as it is, with its mapping and a start posture (robosuite's own
/// initial postures).
macro_rules! robosuite_arm {
    ($name:ident, $robot:literal, $names:expr, $start:expr) => {
        #[derive(Clone, Debug)]
        struct $name(SerialArm);

        impl std::ops::Deref for $name {
            type Target = SerialArm;

            fn deref(&self) -> &SerialArm {
                &self.0
            }
        }

        impl Component for $name {
            fn declaration() -> Declaration {
                Declaration::new(stringify!($name)).mjcf_file(robosuite($robot))
            }

            fn interfaces(interfaces: &mut Interfaces<Self>) {
                interfaces.add::<Sim>();
            }
        }

        impl Interface<Sim> for $name {
            async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
                SerialArm::bind_sim(bind, &$names, Some(&$start), DEFAULT_STIFFNESS).map($name)
            }
        }
    };
}

robosuite_arm!(
    Panda,
    "panda",
    SerialNames::ROBOSUITE_PANDA,
    [0.0, 0.196, 0.0, -2.618, 0.0, 2.942, 0.785]
);
robosuite_arm!(
    Iiwa,
    "iiwa",
    SerialNames::ROBOSUITE_IIWA,
    [0.0, 0.35, 0.0, -1.75, 0.0, 1.05, 0.0]
);
robosuite_arm!(
    Kinova3,
    "kinova3",
    SerialNames::ROBOSUITE_KINOVA3,
    [0.0, 0.65, 0.0, 1.89, 0.0, 0.6, -1.571]
);

/// What a run of the motions saw: the arm's joints at every tick, and the worst distance of
/// MuJoCo's TCP from the line.
struct Run {
    trajectory: Vec<Vec<f64>>,
    off_line: f64,
}

async fn motions(pl: &Pl, arm: &SerialArm) -> Result<Run, BoxError> {
    let start = arm.start().to_vec();
    let limits = arm.limits();
    let mut trajectory = Vec::new();
    let targets: Vec<Vec<f64>> = [0.3, -0.25, 0.0]
        .iter()
        .map(|offset| start.iter().map(|q| q + offset).collect())
        .collect();
    for target in &targets {
        {
            let watch = pl.wait_forever().on_tick(|| trajectory.push(arm.q()));
            tokio::select! {
                biased;
                result = arm.move_j(target.clone()) => result?,
                _ = watch => {}
            }
        }
        let error = arm
            .q()
            .iter()
            .zip(target)
            .map(|(q, t)| (q - t).abs())
            .fold(0.0, f64::max);
        assert!(error < 1e-3, "{error} rad from {target:?}");
        pl.wait_seconds(0.5).await?;
        assert!(arm.is_at(target), "sagged to {:?}", arm.q());
    }
    let from = arm.tcp_pose();
    let mut to = from;
    to.translation.vector += Vector3::new(0.1, -0.1, -0.1414);
    let a = from.translation.vector;
    let b = to.translation.vector;
    let mut off_line: f64 = 0.0;
    {
        let watch = pl.wait_forever().on_tick(|| {
            let q = arm.q();
            let p = arm.tcp_pose().translation.vector;
            let along = ((p - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
            off_line = off_line.max((p - (a + along * (b - a))).norm());
            trajectory.push(q);
        });
        tokio::select! {
            biased;
            result = arm.move_l(to) => result?,
            _ = watch => {}
        }
    }
    assert!(arm.is_at_pose(&to), "ended at {:?}", arm.tcp_pose());
    // No drift in the null space: the joints the line ends at are those one solve from the
    // line's start finds, however many steps the line took.
    let solved = arm.solve(&to, &targets[2])?;
    let drift = arm
        .q()
        .iter()
        .zip(&solved)
        .map(|(q, s)| (q - s).abs())
        .fold(0.0, f64::max);
    assert!(
        drift < 2e-3,
        "the line ends {drift} rad from one solve's joints"
    );
    for q in &trajectory {
        for (q, [lower, upper]) in q.iter().zip(&limits) {
            assert!(
                (lower..=upper).contains(&q),
                "{q} outside [{lower}, {upper}]"
            );
        }
    }
    Ok(Run {
        trajectory,
        off_line,
    })
}

/// The motions on arm `A`, in a world of its own.
fn run<A: Component + Clone + std::ops::Deref<Target = SerialArm>>() -> Run {
    let seen = std::rc::Rc::new(std::cell::RefCell::new(None));
    let keep = std::rc::Rc::clone(&seen);
    yarok::platform()
        .world::<A>()
        .behaviour(move |pl| {
            let keep = std::rc::Rc::clone(&keep);
            async move {
                let arm: A = pl.get("/")?;
                *keep.borrow_mut() = Some(motions(&pl, &arm).await?);
                Ok(())
            }
        })
        .run()
        .unwrap();
    seen.take().expect("the motions ran")
}

fn drives<A: Component + Clone + std::ops::Deref<Target = SerialArm>>() {
    let first = run::<A>();
    println!(
        "{}: {} ticks, TCP at most {:.3} mm off the line",
        std::any::type_name::<A>(),
        first.trajectory.len(),
        first.off_line * 1e3
    );
    assert!(first.off_line < 1e-3, "{} m off the line", first.off_line);
    let second = run::<A>();
    let bits = |run: &Run| -> Vec<u64> {
        run.trajectory
            .iter()
            .flatten()
            .map(|q| q.to_bits())
            .collect()
    };
    assert!(bits(&first) == bits(&second), "two runs differ");
}

#[test]
fn robosuites_panda_moves_as_a_ur_arm_does() {
    drives::<Panda>();
}

#[test]
fn robosuites_iiwa_moves_as_a_ur_arm_does() {
    drives::<Iiwa>();
}

#[test]
fn robosuites_kinova3_moves_as_a_ur_arm_does() {
    drives::<Kinova3>();
}

/// A pose out of reach, and a line over the base (where the first joint would have to turn
/// half a turn at once), are errors when asked, and the arm has not moved.
#[test]
fn an_unreachable_target_or_a_singular_line_is_refused_before_anything_moves() {
    yarok::platform()
        .world::<Panda>()
        .behaviour(|pl| async move {
            let arm: Panda = pl.get("/")?;
            let start = arm.q();
            let far = Isometry3::translation(3.0, 0.0, 0.5) * arm.tcp_pose().rotation;
            let error = arm.move_l(far).await.unwrap_err();
            assert!(
                matches!(error, SerialMotionError::Unreachable(_)),
                "{error}"
            );
            let error = arm.move_j_pose(far).await.unwrap_err();
            assert!(
                matches!(error, SerialMotionError::Unreachable(_)),
                "{error}"
            );
            let mut across = arm.tcp_pose();
            across.translation.vector.x = -across.translation.vector.x;
            across.translation.vector.y = 0.0;
            let error = arm.move_l(across).await.unwrap_err();
            assert!(
                matches!(
                    error,
                    SerialMotionError::Singular { .. } | SerialMotionError::Unreachable(_)
                ),
                "{error}"
            );
            let error = arm.move_j(vec![9.0; 7]).await.unwrap_err();
            assert!(matches!(error, SerialMotionError::InvalidTarget { .. }));
            pl.wait_seconds(0.1).await?;
            assert!(arm.is_at(&start), "moved to {:?}", arm.q());
            Ok(())
        })
        .run()
        .unwrap();
}
