//! Any serial arm, unmodified, driven with the UR arms' motions: every fixed-base arm of
//! robosuite 1.5.2 (files from the installed `robosuite` package, none with gravity
//! compensation; torque motors of their own strengths, joints with damping, dry friction and
//! links as light as 1e-6 kg·m²), bare and with the gripper robosuite mounts on it, each makes
//! three `move_j` motions and a 20 cm `move_l` under gravity at the default speeds: every motion
//! arrives within 1e-3 rad and holds there, the TCP (MuJoCo's, not ours) stays within 1 mm of
//! the straight line, no joint ever leaves its limits, and two runs move the arm identically,
//! bit for bit. Motions an arm's motors cannot follow, targets out of reach and lines through a
//! singularity are errors, in words, before anything moves; a stopped arm stays where it
//! stopped; mappings that cannot work are refused when the arm binds.

use std::path::PathBuf;

use yarok::components::robots::serial::{
    DEFAULT_STIFFNESS, SerialArm, SerialIkError, SerialMotionError, SerialNames, StuckCause,
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

/// What a run of the motions saw: the arm's joints at every tick, and the worst distance of
/// MuJoCo's TCP from the line.
struct Run {
    trajectory: Vec<Vec<f64>>,
    off_line: f64,
}

/// An error, when `condition` does not hold, saying what was seen.
fn check(condition: bool, seen: impl FnOnce() -> String) -> Result<(), BoxError> {
    if condition {
        Ok(())
    } else {
        Err(seen().into())
    }
}

/// The furthest any joint of `q` is from `target`.
fn furthest(q: &[f64], target: &[f64]) -> f64 {
    q.iter()
        .zip(target)
        .map(|(q, t)| (q - t).abs())
        .fold(0.0, f64::max)
}

/// Three joint motions (every joint 0.3 rad one way, 0.25 the other, back to the start), each
/// held for half a second, then a 20 cm line, at the default speeds.
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
        let error = furthest(&arm.q(), target);
        check(error < 1e-3, || format!("{error} rad from {target:?}"))?;
        pl.wait_seconds(0.5).await?;
        check(arm.is_at(target), || format!("sagged to {:?}", arm.q()))?;
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
    check(arm.is_at_pose(&to), || {
        format!("line ended at {:?}", arm.tcp_pose())
    })?;
    check(off_line < 1e-3, || {
        format!("the TCP left the line by {off_line} m")
    })?;
    // No drift in the null space: the joints the line ends at are those one solve from the
    // line's start finds, however many steps the line took.
    let drift = furthest(&arm.q(), &arm.solve(&to, &targets[2])?);
    check(drift < 2e-3, || {
        format!("the line ends {drift} rad from one solve's joints")
    })?;
    for q in &trajectory {
        for (q, [lower, upper]) in q.iter().zip(&limits) {
            check((lower..=upper).contains(&q), || {
                format!("{q} outside [{lower}, {upper}]")
            })?;
        }
    }
    Ok(Run {
        trajectory,
        off_line,
    })
}

/// An arm of robosuite's as a case of the every-arm test: its file, mapping, start, and the
/// default gripper robosuite mounts on it (its file and the body it hangs from).
/// A gripper file of robosuite's mounted on an arm's hand body, with what the component that
/// wraps it states over the file (nothing, or a setting the file gets wrong).
#[derive(Clone, Copy)]
struct Mounted {
    file: &'static str,
    hand: &'static str,
    stated: &'static str,
}

impl Mounted {
    const fn as_it_is(file: &'static str, hand: &'static str) -> Self {
        Self {
            file,
            hand,
            stated: "",
        }
    }
}

struct Case {
    robot: &'static str,
    names: SerialNames,
    start: &'static [f64],
    gripper: Option<Mounted>,
    /// A bimanual robot's other arm, which holds its start meanwhile.
    other: Option<(SerialNames, &'static [f64])>,
}

/// A posture of Tiago's arms from which each can draw the test's line.
const TIAGO_START: &[f64] = &[0.6, -0.7, 2.24, 1.33, -1.01, -0.79];

/// Postures of Baxter's arms from which each moves clear of its torso and of the other.
const BAXTER_RIGHT_START: &[f64] = &[-0.04, -1.21, 0.33, 1.09, 0.45, 1.19, -0.8];
const BAXTER_LEFT_START: &[f64] = &[0.58, -1.27, -0.24, 0.98, -0.77, 1.67, 0.89];

const PANDA: usize = 0;
const IIWA: usize = 2;
const KINOVA3: usize = 4;
const UR5E: usize = 5;
const SPOT_ARM: usize = 11;
const TIAGO_RIGHT: usize = 9;

const CASES: [Case; 12] = [
    Case {
        robot: "panda",
        names: SerialNames::ROBOSUITE_PANDA,
        start: &[0.0, 0.196, 0.0, -2.618, 0.0, 2.942, 0.785],
        gripper: Some(Mounted::as_it_is("panda_gripper", "right_hand")),
        other: None,
    },
    Case {
        robot: "sawyer",
        names: SerialNames::ROBOSUITE_SAWYER,
        start: &[0.0, -1.18, 0.0, 2.18, 0.0, 0.57, -1.57],
        gripper: Some(Mounted::as_it_is("rethink_gripper", "right_hand")),
        other: None,
    },
    Case {
        robot: "iiwa",
        names: SerialNames::ROBOSUITE_IIWA,
        start: &[0.0, 0.35, 0.0, -1.75, 0.0, 1.05, 0.0],
        gripper: Some(Mounted::as_it_is("robotiq_gripper_140", "right_hand")),
        other: None,
    },
    Case {
        robot: "jaco",
        names: SerialNames::ROBOSUITE_JACO,
        start: &[3.192, 3.68, 0.0, 1.17, 0.05, 3.76, std::f64::consts::PI],
        gripper: Some(Mounted::as_it_is("jaco_three_finger_gripper", "right_hand")),
        other: None,
    },
    Case {
        robot: "kinova3",
        names: SerialNames::ROBOSUITE_KINOVA3,
        start: &[0.0, 0.65, 0.0, 1.89, 0.0, 0.6, -1.571],
        gripper: None,
        other: None,
    },
    Case {
        robot: "ur5e",
        names: SerialNames::ROBOSUITE_UR5E,
        start: &[-0.47, -1.735, 2.48, -2.275, -1.59, -1.991],
        gripper: None,
        other: None,
    },
    Case {
        robot: "xarm7",
        names: SerialNames::ROBOSUITE_XARM7,
        start: &[0.0, 0.0, 0.0, 1.225, 0.0, 1.225, 0.0],
        gripper: None,
        other: None,
    },
    Case {
        robot: "baxter",
        names: SerialNames::ROBOSUITE_BAXTER_RIGHT,
        start: BAXTER_RIGHT_START,
        gripper: Some(Mounted::as_it_is("rethink_gripper", "right_hand")),
        other: Some((SerialNames::ROBOSUITE_BAXTER_LEFT, BAXTER_LEFT_START)),
    },
    Case {
        robot: "baxter",
        names: SerialNames::ROBOSUITE_BAXTER_LEFT,
        start: BAXTER_LEFT_START,
        gripper: Some(Mounted::as_it_is("rethink_gripper", "left_hand")),
        other: Some((SerialNames::ROBOSUITE_BAXTER_RIGHT, BAXTER_RIGHT_START)),
    },
    Case {
        robot: "tiago",
        names: SerialNames::ROBOSUITE_TIAGO_RIGHT,
        start: TIAGO_START,
        gripper: None,
        other: Some((SerialNames::ROBOSUITE_TIAGO_LEFT, TIAGO_START)),
    },
    Case {
        robot: "tiago",
        names: SerialNames::ROBOSUITE_TIAGO_LEFT,
        start: TIAGO_START,
        gripper: None,
        other: Some((SerialNames::ROBOSUITE_TIAGO_RIGHT, TIAGO_START)),
    },
    Case {
        robot: "spot_arm",
        names: SerialNames::ROBOSUITE_SPOT_ARM,
        start: &[0.0, -1.2, 1.85, 0.0, 0.862, 0.0],
        // robosuite's `bd_gripper.xml` sets the world's gravity to zero (`<option
        // gravity="0 0 0"/>`), which a component may not (see
        // `spots_gripper_file_would_switch_gravity_off_and_is_refused_naming_it`): it is
        // mounted with the world's gravity stated over it, as a file's angle unit is.
        gripper: Some(Mounted {
            file: "bd_gripper",
            hand: "right_hand",
            stated: r#"<option gravity="0 0 -9.81"/>"#,
        }),
        other: None,
    },
];

/// Case `I`'s arm, as its file is.
#[derive(Clone, Debug)]
struct CaseArm<const I: usize>(SerialArm);

impl<const I: usize> std::ops::Deref for CaseArm<I> {
    type Target = SerialArm;

    fn deref(&self) -> &SerialArm {
        &self.0
    }
}

impl<const I: usize> Component for CaseArm<I> {
    fn declaration() -> Declaration {
        Declaration::new(format!("{}_arm", CASES[I].robot)).mjcf_file(robosuite(CASES[I].robot))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl<const I: usize> Interface<Sim> for CaseArm<I> {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let case = &CASES[I];
        if let Some((other, start)) = case.other {
            // Its controller holds it on every tick; the handle is not needed.
            SerialArm::bind_sim(bind, &other, Some(start), DEFAULT_STIFFNESS)?;
        }
        SerialArm::bind_sim(bind, &case.names, Some(case.start), DEFAULT_STIFFNESS).map(Self)
    }
}

/// Case `I`'s default gripper's file, as it is.
struct CaseGripperFile<const I: usize>;

impl<const I: usize> Component for CaseGripperFile<I> {
    fn declaration() -> Declaration {
        let gripper = CASES[I].gripper.expect("the case has a gripper").file;
        Declaration::new(format!("{gripper}_file")).mjcf_file(
            peers::package("robosuite")
                .join("models/assets/grippers")
                .join(format!("{gripper}.xml")),
        )
    }
}

/// Case `I`'s default gripper: its file with what the case states over it (nothing drives
/// it).
struct CaseGripper<const I: usize>;

impl<const I: usize> Component for CaseGripper<I> {
    fn declaration() -> Declaration {
        let mounted = CASES[I].gripper.expect("the case has a gripper");
        Declaration::new(mounted.file)
            .extends::<CaseGripperFile<I>>()
            .template(format!("<mujoco>{}</mujoco>", mounted.stated))
    }
}

/// Case `I`'s arm, with its gripper mounted when `GRIPPER`.
struct CaseWorld<const I: usize, const GRIPPER: bool>;

impl<const I: usize, const GRIPPER: bool> Component for CaseWorld<I, GRIPPER> {
    fn declaration() -> Declaration {
        let arm = CaseArm::<I>::declaration().tag().to_owned();
        let mut declaration = Declaration::new("case_world").uses::<CaseArm<I>>();
        let mut mounted = String::new();
        if GRIPPER {
            declaration = declaration.uses::<CaseGripper<I>>();
            let Mounted { file, hand, .. } = CASES[I].gripper.expect("the case has a gripper");
            mounted = format!(r#"<{file} name="gripper" parent="{hand}"/>"#);
        }
        // MuJoCo's gravity, stated: a component may then state it too (Spot's gripper does).
        declaration.template(format!(
            r#"<mujoco><option gravity="0 0 -9.81"/>
                 <worldbody><{arm} name="arm">{mounted}</{arm}></worldbody></mujoco>"#
        ))
    }
}

/// Runs `behaviour` in world `W` with `settings` (`--set` arguments): what it returned.
fn outcome_in<W: Component, T: 'static>(
    settings: &[String],
    behaviour: impl AsyncFn(&Pl) -> Result<T, BoxError> + Clone + 'static,
) -> Result<T, String> {
    let seen = std::rc::Rc::new(std::cell::RefCell::new(None));
    let keep = std::rc::Rc::clone(&seen);
    yarok::platform()
        .world::<W>()
        .args(settings.iter().cloned())
        .map_err(|error| error.to_string())?
        .behaviour(move |pl| {
            let keep = std::rc::Rc::clone(&keep);
            let behaviour = behaviour.clone();
            async move {
                *keep.borrow_mut() = Some(behaviour(&pl).await?);
                Ok(())
            }
        })
        .run()
        .map_err(|error| error.to_string())?;
    seen.take()
        .ok_or_else(|| "the behaviour did not finish".to_owned())
}

/// Runs `behaviour` on case `I`'s arm (with its gripper when `GRIPPER`) in a world of its own.
fn with_case<const I: usize, const GRIPPER: bool, T: 'static>(
    behaviour: impl AsyncFn(&Pl, &SerialArm) -> Result<T, BoxError> + Clone + 'static,
) -> Result<T, String> {
    outcome_in::<CaseWorld<I, GRIPPER>, T>(&[], async move |pl| {
        let arm: CaseArm<I> = pl.get("/arm")?;
        behaviour(pl, &arm).await
    })
}

/// The motions on case `I`'s arm.
fn drive<const I: usize, const GRIPPER: bool>() -> Result<Run, String> {
    with_case::<I, GRIPPER, _>(async |pl, arm| motions(pl, arm).await)
}

/// The motions twice on case `I`'s bare arm: identical, bit for bit.
fn drives_identically<const I: usize>() {
    let first = drive::<I, false>().unwrap();
    let second = drive::<I, false>().unwrap();
    let bits = |run: &Run| -> Vec<u64> {
        run.trajectory
            .iter()
            .flatten()
            .map(|q| q.to_bits())
            .collect()
    };
    println!(
        "{}: {} ticks, TCP at most {:.3} mm off the line",
        CASES[I].robot,
        first.trajectory.len(),
        first.off_line * 1e3
    );
    assert!(bits(&first) == bits(&second), "two runs differ");
}

#[test]
fn robosuites_panda_moves_identically_twice() {
    drives_identically::<PANDA>();
}

#[test]
fn robosuites_iiwa_moves_identically_twice() {
    drives_identically::<IIWA>();
}

#[test]
fn robosuites_kinova3_moves_identically_twice() {
    drives_identically::<KINOVA3>();
}

/// Every case, bare and with its gripper: `(case, with the gripper, outcome)`.
macro_rules! every_case {
    ($($i:expr),*) => {
        vec![
            $((CASES[$i].robot, CASES[$i].names.tcp, false, drive::<{ $i }, false>().map(drop)),)*
            $((CASES[$i].robot, CASES[$i].names.tcp, true, if CASES[$i].gripper.is_some() {
                drive::<{ $i }, true>().map(drop)
            } else {
                Ok(())
            }),)*
        ]
    };
}

#[test]
fn every_fixed_base_arm_of_robosuite_drives_bare_and_with_its_gripper() {
    let outcomes = every_case!(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11);
    let mut failed = Vec::new();
    for (robot, hand, gripper, outcome) in &outcomes {
        let mounted = if *gripper { "with its gripper" } else { "bare" };
        println!("{robot} ({hand}) {mounted}: {outcome:?}");
        if let Err(error) = outcome {
            failed.push(format!("{robot} ({hand}) {mounted}: {error}"));
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}

/// A pose 3 m away is refused by how far the arm's nearest reach is from it (not from the
/// first point of the line); a line over the base by where along it the joints would jump; a
/// joint target beyond the limits by the joint and its limits. Nothing moves.
#[test]
fn refusals_say_what_is_wrong_and_nothing_moves() {
    let messages = with_case::<PANDA, false, _>(async |pl, arm| {
        let start = arm.q();
        let far = Isometry3::translation(3.0, 0.0, 0.5) * arm.tcp_pose().rotation;
        let line = arm.move_l(far).await.unwrap_err();
        let SerialMotionError::Unreachable(SerialIkError::Unreachable { metres, .. }) = line else {
            panic!("{line}");
        };
        assert!(
            metres > 1.5,
            "the nearest reach is {metres} m from a pose 3 m away"
        );
        let joint_move = arm.move_j_pose(far).await.unwrap_err();
        let beyond = arm.move_j(vec![9.0; 7]).await.unwrap_err();
        pl.wait_seconds(0.1).await?;
        assert!(arm.is_at(&start), "moved to {:?}", arm.q());
        Ok([line.to_string(), joint_move.to_string(), beyond.to_string()])
    })
    .unwrap();
    // The UR5e's first joint turns a whole turn either way: the pose half a turn about the
    // base is reachable, but the line to it passes over the base, where that joint would jump.
    let singular = with_case::<UR5E, false, _>(async |pl, arm| {
        let start = arm.q();
        let across = Isometry3::rotation(Vector3::z() * std::f64::consts::PI) * arm.tcp_pose();
        let singular = arm.move_l(across).await.unwrap_err();
        pl.wait_seconds(0.1).await?;
        assert!(arm.is_at(&start), "moved to {:?}", arm.q());
        Ok(singular)
    })
    .unwrap();
    println!("{singular}");
    assert!(
        matches!(
            singular,
            SerialMotionError::Singular { .. } | SerialMotionError::LeavesReach { .. }
        ),
        "{singular}"
    );
    for message in &messages {
        println!("{message}");
    }
    assert!(
        messages[0].contains("the nearest the arm gets is 2."),
        "{}",
        messages[0]
    );
    assert_eq!(messages[0], messages[1]);
    let singular = singular.to_string();
    assert!(
        (singular.contains("the line passes a singularity or a joint limit")
            || singular.contains("the line leaves the arm's reach"))
            && singular.contains("% of its length"),
        "{singular}"
    );
    assert!(
        messages[2].contains(r#"joint "arm/joint1" at 9 is outside its limits [-2.8973, 2.8973]"#),
        "{}",
        messages[2]
    );
}

/// robosuite's Tiago right arm: joint 2's damping (100 N·m·s/rad) takes twice what its
/// ±50 N·m motor gives at the default joint speed. A motion at that speed, chosen, is refused
/// naming the joint before anything moves; at the defaults it is slowed to what the motors give
/// and arrives, no joint passing its limits (the every-arm test); stopped, or dropped, the arm
/// holds where it stopped: within 1e-3 rad over the next second, `is_moving` false.
#[test]
fn a_saturating_arm_is_slowed_or_refused_and_stays_where_it_stops() {
    let (refusal, drifts) = with_case::<TIAGO_RIGHT, false, _>(async |pl, arm| {
        let start = arm.q();
        let mut target = start.clone();
        target[1] += 1.0;
        let refusal = arm
            .move_j(target.clone())
            .speed(1.05)
            .acceleration(1.4)
            .await
            .unwrap_err();
        pl.wait_seconds(0.1).await?;
        assert!(arm.is_at(&start), "moved to {:?}", arm.q());
        let mut drifts = Vec::new();
        for dropped in [false, true] {
            let away: Vec<f64> = arm.q().iter().map(|q| q + 0.3).collect();
            if dropped {
                let motion = arm.move_j(away);
                tokio::select! {
                    _ = motion => panic!("the motion ended before it was dropped"),
                    _ = pl.wait_seconds(0.4) => {}
                }
            } else {
                arm.move_j(away).start()?;
                pl.wait_seconds(0.4).await?;
                arm.stop();
            }
            pl.wait(|| !arm.is_moving()).timeout(2.0).await?;
            let stopped = arm.q();
            let mut moving = false;
            pl.wait_seconds(1.0)
                .on_tick(|| moving |= arm.is_moving())
                .await?;
            assert!(!moving, "is_moving after the arm came to rest");
            drifts.push(furthest(&arm.q(), &stopped));
        }
        Ok((refusal, drifts))
    })
    .unwrap();
    println!("{refusal}\ndrift over the second after a stop, a drop: {drifts:?}");
    let SerialMotionError::Overloaded { ref joint, .. } = refusal else {
        panic!("{refusal}");
    };
    assert_eq!(joint, "arm_right_2_joint", "{refusal}");
    assert!(
        refusal
            .to_string()
            .contains("ask a lower speed or acceleration"),
        "{refusal}"
    );
    for drift in drifts {
        assert!(drift <= 1e-3, "drifted {drift} rad after stopping");
    }
}

const PANDA_JOINTS: [&str; 7] = [
    "joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint7",
];

/// Mappings of robosuite's Panda that cannot work, and the words each is refused with.
const MISMAPPED: [(SerialNames, &str); 4] = [
    (
        SerialNames {
            joints: &PANDA_JOINTS,
            actuators: &[
                "torq_j2", "torq_j1", "torq_j3", "torq_j4", "torq_j5", "torq_j6", "torq_j7",
            ],
            tcp: "right_hand",
        },
        r#"actuator "torq_j2" drives joint "joint2", not "joint1": the mapping's actuators are in the order of its joints (are two swapped?)"#,
    ),
    (
        SerialNames {
            joints: &[
                "joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint6",
            ],
            actuators: &[
                "torq_j1", "torq_j2", "torq_j3", "torq_j4", "torq_j5", "torq_j6", "torq_j7",
            ],
            tcp: "right_hand",
        },
        r#""joint6" is named twice in the mapping"#,
    ),
    (
        SerialNames {
            joints: &PANDA_JOINTS,
            actuators: &[
                "torq_j1", "torq_j2", "torq_j3", "torq_j4", "torq_j5", "torq_j6", "torq_j7",
            ],
            tcp: "link3",
        },
        r#"the TCP "link3" is not carried by the arm's last joint "joint7""#,
    ),
    (
        SerialNames {
            joints: &PANDA_JOINTS,
            actuators: &[
                "torq_j1", "torq_j2", "torq_j3", "torq_j4", "torq_j5", "torq_j6", "torq_j7",
            ],
            tcp: "right_hnad",
        },
        r#"the TCP "right_hnad" is neither a site nor a body of its template (sites: it has `right_center`; bodies: did you mean `right_hand`?)"#,
    ),
];

/// robosuite's Panda bound with mapping `M` of [`MISMAPPED`].
#[derive(Clone)]
struct Mismapped<const M: usize>;

impl<const M: usize> Component for Mismapped<M> {
    fn declaration() -> Declaration {
        Declaration::new("arm").mjcf_file(robosuite("panda"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl<const M: usize> Interface<Sim> for Mismapped<M> {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        SerialArm::bind_sim(bind, &MISMAPPED[M].0, None, DEFAULT_STIFFNESS).map(|_| Self)
    }
}

/// The error composing or binding world `W` gives; its behaviour never runs.
fn bind_refusal<W: Component>() -> String {
    yarok::platform()
        .world::<W>()
        .behaviour(|_| async { panic!("a world that cannot work was bound") })
        .run()
        .unwrap_err()
        .to_string()
}

/// The error binding mapping `M` gives; the arm never runs.
fn refusal<const M: usize>() -> String {
    let error = bind_refusal::<Mismapped<M>>();
    assert!(error.contains(MISMAPPED[M].1), "{error}");
    error
}

/// Swapped actuators, a joint named twice, a TCP on a body the arm does not carry, a TCP the
/// file lacks: each refused when the arm binds, in words that name the entry at fault.
#[test]
fn mappings_that_cannot_work_are_refused_before_anything_moves() {
    for refusal in [
        refusal::<0>(),
        refusal::<1>(),
        refusal::<2>(),
        refusal::<3>(),
    ] {
        println!("{refusal}");
    }
}

/// Spot's gripper file sets the world's gravity to zero; mounted on the arm, it is refused at
/// that attribute (a component may not change the whole world).
#[test]
fn spots_gripper_file_would_switch_gravity_off_and_is_refused_naming_it() {
    struct SpotGripper;

    impl Component for SpotGripper {
        fn declaration() -> Declaration {
            Declaration::new("bd_gripper").mjcf_file(
                peers::package("robosuite").join("models/assets/grippers/bd_gripper.xml"),
            )
        }
    }

    struct SpotWithGripper;

    impl Component for SpotWithGripper {
        fn declaration() -> Declaration {
            Declaration::new("spot_world")
                .uses::<CaseArm<SPOT_ARM>>()
                .uses::<SpotGripper>()
                .template(
                    r#"<mujoco><worldbody><spot_arm_arm name="arm">
                         <bd_gripper name="gripper" parent="right_hand"/>
                       </spot_arm_arm></worldbody></mujoco>"#,
                )
        }
    }

    let error = bind_refusal::<SpotWithGripper>();
    assert!(
        error.contains("bd_gripper.xml:3:11") && error.contains("option/@gravity"),
        "{error}"
    );
}

/// dm_control's Kinova Jaco arm file, as it is (it declares no actuators: dm_control adds them
/// in Python).
struct DmControlJacoFile;

impl Component for DmControlJacoFile {
    fn declaration() -> Declaration {
        Declaration::new("dm_jaco_file")
            .mjcf_file(peers::package("dm_control").join("third_party/kinova/jaco_arm.xml"))
    }
}

/// The file unmodified, with torque motors of the strengths dm_control gives its actuators
/// (Kinova's datasheet peaks: 30.5 N·m for the three large joints, 6.8 for the small ones).
#[derive(Clone, Debug)]
struct DmControlJaco(SerialArm);

const DM_CONTROL_JACO: SerialNames = SerialNames {
    joints: &[
        "joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6",
    ],
    actuators: &[
        "motor_1", "motor_2", "motor_3", "motor_4", "motor_5", "motor_6",
    ],
    tcp: "wristsite",
};

impl Component for DmControlJaco {
    fn declaration() -> Declaration {
        Declaration::new("dm_jaco")
            .extends::<DmControlJacoFile>()
            .template(
                r#"<mujoco><actuator>
                     <motor name="motor_1" joint="joint_1" ctrlrange="-30.5 30.5"/>
                     <motor name="motor_2" joint="joint_2" ctrlrange="-30.5 30.5"/>
                     <motor name="motor_3" joint="joint_3" ctrlrange="-30.5 30.5"/>
                     <motor name="motor_4" joint="joint_4" ctrlrange="-6.8 6.8"/>
                     <motor name="motor_5" joint="joint_5" ctrlrange="-6.8 6.8"/>
                     <motor name="motor_6" joint="joint_6" ctrlrange="-6.8 6.8"/>
                   </actuator></mujoco>"#,
            )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for DmControlJaco {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let start = [0.0, 2.5, 4.0, 0.5, 0.5, 0.0];
        SerialArm::bind_sim(bind, &DM_CONTROL_JACO, Some(&start), DEFAULT_STIFFNESS).map(Self)
    }
}

/// dm_control's Jaco (heavy armatures, 1–2 N·m of dry friction a joint, weak wrist motors)
/// makes the motions, and after a stop stays where it stopped.
#[test]
fn dm_controls_jaco_drives_and_stays_where_it_stops() {
    let drift = outcome_in::<DmControlJaco, _>(&[], async |pl| {
        let DmControlJaco(arm) = pl.get("/")?;
        let run = motions(pl, &arm).await?;
        println!(
            "{} ticks, TCP at most {:.3} mm off the line",
            run.trajectory.len(),
            run.off_line * 1e3
        );
        let away: Vec<f64> = arm.q().iter().map(|q| q + 0.3).collect();
        arm.move_j(away).start()?;
        pl.wait_seconds(0.4).await?;
        arm.stop();
        pl.wait(|| !arm.is_moving()).timeout(2.0).await?;
        let stopped = arm.q();
        pl.wait_seconds(1.0).await?;
        Ok(furthest(&arm.q(), &stopped))
    })
    .unwrap();
    assert!(drift <= 1e-3, "drifted {drift} rad after stopping");
}

/// gym-aloha's bimanual ViperX 300s (LeRobot's ALOHA simulation), its file unmodified: 16
/// position servos without names, each found by the joint it drives.
#[derive(Clone, Debug)]
struct GymAloha {
    left: SerialArm,
    right: SerialArm,
}

/// One ViperX of the pair, its joints base to wrist and its TCP between the fingers.
const fn viperx(joints: &'static [&'static str], tcp: &'static str) -> SerialNames {
    SerialNames {
        joints,
        actuators: &[],
        tcp,
    }
}

const ALOHA_LEFT: SerialNames = viperx(
    &[
        "vx300s_left/waist",
        "vx300s_left/shoulder",
        "vx300s_left/elbow",
        "vx300s_left/forearm_roll",
        "vx300s_left/wrist_angle",
        "vx300s_left/wrist_rotate",
    ],
    "left_cam_focus",
);

const ALOHA_RIGHT: SerialNames = viperx(
    &[
        "vx300s_right/waist",
        "vx300s_right/shoulder",
        "vx300s_right/elbow",
        "vx300s_right/forearm_roll",
        "vx300s_right/wrist_angle",
        "vx300s_right/wrist_rotate",
    ],
    "right_cam_focus",
);

/// The start gym-aloha's keyframe gives each arm.
const ALOHA_START: [f64; 6] = [0.0, -0.96, 1.16, 0.0, -0.3, 0.0];

impl Component for GymAloha {
    fn declaration() -> Declaration {
        Declaration::new("gym_aloha")
            .mjcf_file(peers::package("gym_aloha").join("assets/bimanual_viperx_transfer_cube.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for GymAloha {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let start = Some(&ALOHA_START[..]);
        Ok(Self {
            left: SerialArm::bind_sim(bind, &ALOHA_LEFT, start, DEFAULT_STIFFNESS)?,
            right: SerialArm::bind_sim(bind, &ALOHA_RIGHT, start, DEFAULT_STIFFNESS)?,
        })
    }
}

/// Both arms of gym-aloha's file move through their own unnamed position servos: each makes a
/// joint motion and arrives under gravity while the other holds its start.
#[test]
fn gym_alohas_unnamed_position_servos_drive_both_arms() {
    yarok::platform()
        .world::<GymAloha>()
        .behaviour(|pl| async move {
            let aloha: GymAloha = pl.get("/")?;
            for (moving, holding) in [(&aloha.left, &aloha.right), (&aloha.right, &aloha.left)] {
                let target: Vec<f64> = ALOHA_START
                    .iter()
                    .zip([0.4, 0.3, -0.3, 0.5, 0.4, 0.6])
                    .map(|(q, offset)| q + offset)
                    .collect();
                moving.move_j(target.clone()).await?;
                pl.wait_seconds(0.5).await?;
                let error = furthest(&moving.q(), &target);
                check(error < 1e-3, || {
                    format!("{error} rad from {target:?}: at {:?}", moving.q())
                })?;
                let drift = furthest(&holding.q(), holding.start());
                check(drift < 1e-3, || {
                    format!("the other arm drifted {drift} rad")
                })?;
                moving.move_j(ALOHA_START.to_vec()).await?;
            }
            Ok(())
        })
        .run()
        .unwrap();
}

/// dm_control's Jaco file, which declares no actuators, bound by its joints' actuators.
#[derive(Clone, Debug)]
struct UnactuatedJaco;

impl Component for UnactuatedJaco {
    fn declaration() -> Declaration {
        DmControlJacoFile::declaration()
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for UnactuatedJaco {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let names = SerialNames {
            actuators: &[],
            ..DM_CONTROL_JACO
        };
        SerialArm::bind_sim(bind, &names, None, DEFAULT_STIFFNESS).map(|_| Self)
    }
}

/// An arm whose joints no actuator drives is refused naming the first such joint.
#[test]
fn a_joint_no_actuator_drives_is_refused_naming_it() {
    let error = bind_refusal::<UnactuatedJaco>();
    assert!(
        error.contains(r#"no actuator drives joint "joint_1": the file declares none on it"#),
        "{error}"
    );
}

/// gym-aloha's end-effector scene: the same ViperX arms, moved by welds to mocap bodies instead
/// of joint actuators.
#[derive(Clone, Debug)]
struct GymAlohaEndEffector;

impl Component for GymAlohaEndEffector {
    fn declaration() -> Declaration {
        Declaration::new("gym_aloha_end_effector").mjcf_file(
            peers::package("gym_aloha")
                .join("assets/bimanual_viperx_end_effector_transfer_cube.xml"),
        )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for GymAlohaEndEffector {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        SerialArm::bind_sim(bind, &ALOHA_LEFT, None, DEFAULT_STIFFNESS).map(|_| Self)
    }
}

/// An arm whose hand a mocap weld moves is refused naming the weld's bodies, not "no actuator".
#[test]
fn an_arm_moved_by_a_mocap_weld_is_refused_naming_the_weld() {
    let error = bind_refusal::<GymAlohaEndEffector>();
    assert!(
        error.contains(
            r#"joint "vx300s_left/waist" has no actuator: the file moves the arm by the weld of mocap body "mocap_left" to "vx300s_left/gripper_link""#
        ),
        "{error}"
    );
}

/// robosuite's bare Panda with a fixed slab `slab` (its centre; 20 × 20 × 2 cm) and, when
/// `WELD`, its hand welded where it is in the model's reference posture (`pinned`).
struct Obstructed<const WELD: bool>;

impl<const WELD: bool> Component for Obstructed<WELD> {
    fn declaration() -> Declaration {
        let arm = CaseArm::<PANDA>::declaration().tag().to_owned();
        let weld = if WELD {
            r#"<equality><weld name="pinned" body1="arm/right_hand"/></equality>"#
        } else {
            ""
        };
        Declaration::new("obstructed_world")
            .uses::<CaseArm<PANDA>>()
            .default("slab", [0.0, 0.0, -1.0])
            .template(format!(
                r#"<mujoco><option gravity="0 0 -9.81"/>
                     <worldbody>
                       <geom name="slab" type="box" size="0.1 0.1 0.01" pos="{{slab}}"/>
                       <{arm} name="arm"/>
                     </worldbody>{weld}</mujoco>"#
            ))
    }
}

/// A straight line 20 cm down from the start in an [`Obstructed`] world with its settings: the
/// motion's error.
fn down_in<const WELD: bool>(settings: &[String]) -> SerialMotionError {
    outcome_in::<Obstructed<WELD>, _>(settings, async |pl| {
        let arm: CaseArm<PANDA> = pl.get("/arm")?;
        let mut below = arm.tcp_pose();
        below.translation.vector.z -= 0.2;
        Ok(arm.move_l(below).await.err())
    })
    .unwrap()
    .expect("the line arrived")
}

/// A motion that stops says what stopped it: a slab 6 cm under the Panda's hand stops a line
/// down, named as a contact between the slab and the arm's link with the force between them;
/// a weld holding the hand stops it, named as the weld; neither is called a saturated actuator.
#[test]
fn a_stopped_motion_names_the_contact_or_the_weld_that_stopped_it() {
    let hand =
        with_case::<PANDA, false, _>(async |_, arm| Ok(arm.tcp_pose().translation.vector)).unwrap();
    let slab = format!("slab=[{},{},{}]", hand.x, hand.y, hand.z - 0.06);
    let blocked = down_in::<false>(&["--set".into(), slab]);
    println!("{blocked}");
    let SerialMotionError::Stuck {
        cause:
            StuckCause::Contact {
                ref bodies,
                normal_force,
                ..
            },
        ..
    } = blocked
    else {
        panic!("{blocked}");
    };
    assert!(bodies.iter().any(|body| body == "world"), "{blocked}");
    assert!(
        bodies.iter().any(|body| body.starts_with("arm/")),
        "{blocked}"
    );
    assert!(normal_force > 1.0, "{blocked}");
    assert!(blocked.to_string().contains("clear the way"), "{blocked}");

    let pinned = down_in::<true>(&[]);
    println!("{pinned}");
    let SerialMotionError::Stuck {
        cause: StuckCause::Constrained { ref name, .. },
        ..
    } = pinned
    else {
        panic!("{pinned}");
    };
    assert_eq!(name.as_deref(), Some("pinned"), "{pinned}");
}

/// A two-link arm turning in the horizontal plane on torque motors, its elbow's limit reaching
/// 0.4 rad inside its range (`margin`), as some files state.
#[derive(Clone, Debug)]
struct MarginArm(SerialArm);

const MARGIN_ARM: SerialNames = SerialNames {
    joints: &["shoulder", "elbow"],
    actuators: &["shoulder_motor", "elbow_motor"],
    tcp: "tip",
};

impl Component for MarginArm {
    fn declaration() -> Declaration {
        Declaration::new("margin_arm").template(
            r#"<mujoco><compiler angle="radian"/><option gravity="0 0 -9.81"/>
                 <worldbody>
                   <body name="upper" pos="0 0 0.5">
                     <joint name="shoulder" axis="0 0 1" range="-2 2" damping="0.5"/>
                     <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03" mass="1"/>
                     <body name="lower" pos="0.3 0 0">
                       <joint name="elbow" axis="0 0 1" range="-2 2" margin="0.4" damping="0.5"/>
                       <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03" mass="1"/>
                       <site name="tip" pos="0.3 0 0"/>
                     </body>
                   </body>
                 </worldbody>
                 <actuator>
                   <motor name="shoulder_motor" joint="shoulder" ctrlrange="-50 50"/>
                   <motor name="elbow_motor" joint="elbow" ctrlrange="-50 50"/>
                 </actuator>
               </mujoco>"#,
        )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for MarginArm {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        SerialArm::bind_sim(bind, &MARGIN_ARM, Some(&[0.0, 0.0]), DEFAULT_STIFFNESS).map(Self)
    }
}

/// A joint move to 1.9 rad, inside the elbow's range but within its limit's margin, stops where
/// the limit pushes back, and says so, naming the joint's limit.
#[test]
fn a_motion_into_a_limits_margin_names_the_limit() {
    let stopped = outcome_in::<MarginArm, _>(&[], async |pl| {
        let MarginArm(arm) = pl.get("/")?;
        Ok(arm.move_j(vec![0.0, 1.9]).await.err())
    })
    .unwrap()
    .expect("the motion arrived inside the limit's margin");
    println!("{stopped}");
    let SerialMotionError::Stuck {
        cause: StuckCause::Limit { ref what, .. },
        ref joint,
        ..
    } = stopped
    else {
        panic!("{stopped}");
    };
    assert_eq!(joint, "elbow", "{stopped}");
    assert_eq!(what, r#"joint "elbow""#, "{stopped}");
}
