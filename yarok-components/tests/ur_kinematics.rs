//! The UR arms' closed-form kinematics: forward kinematics against the reference table, inverse
//! kinematics round trips on random poses, unreachable, singular and non-finite poses, joint
//! limits with their ±2π copies, and UR pose vectors.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use yarok_components::robots::ur::{
    DhParameters, IkError, Joints, Kinematics, pose_from_vector, pose_to_vector,
};
use yarok_components::tactile::noise::SplitMix64;

fn random_joints(random: &mut SplitMix64) -> Joints {
    std::array::from_fn(|i| {
        let limit = if i == 2 { PI } else { TAU };
        random.uniform(-limit, limit)
    })
}

/// Position and rotation errors between two poses (metres, radians).
fn errors(a: &Isometry3<f64>, b: &Isometry3<f64>) -> (f64, f64) {
    (
        (a.translation.vector - b.translation.vector).norm(),
        a.rotation.angle_to(&b.rotation),
    )
}

/// Tool0 positions of the reference table (computed there from the DH parameters, 4 decimals).
#[test]
fn forward_kinematics_matches_the_reference_table() {
    let upright = [0.0, -FRAC_PI_2, 0.0, -FRAC_PI_2, 0.0, 0.0];
    let home = [
        -FRAC_PI_2, -FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2, 0.0,
    ];
    let cases = [
        (DhParameters::UR5E, [0.0; 6], [-0.8172, -0.2329, 0.0628]),
        (DhParameters::UR5E, upright, [0.0, -0.2329, 1.0794]),
        (DhParameters::UR5E, home, [-0.1333, 0.4919, 0.4879]),
        (DhParameters::UR5, [0.0; 6], [-0.8173, -0.1915, -0.0055]),
        (DhParameters::UR5, upright, [0.0, -0.1914, 1.0011]),
        (DhParameters::UR5, home, [-0.1091, 0.4869, 0.4319]),
    ];
    for (dh, q, expected) in cases {
        let tool0 = dh.forward(&q);
        let error = (tool0.translation.vector - Vector3::from(expected))
            .abs()
            .max();
        assert!(
            error <= 0.6e-4,
            "{dh:?} at {q:?}: {tool0:?}, expected {expected:?}"
        );
    }
    let z = |q: &Joints| DhParameters::UR5E.forward(q).rotation * Vector3::z();
    assert!((z(&[0.0; 6]) - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-12);
    assert!((z(&home) - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-6);
}

/// 100 000 random configurations of each arm: every solution returned reproduces the pose, and
/// the configuration that made it is among them.
#[test]
fn every_inverse_solution_reproduces_the_pose() {
    let mut random = SplitMix64::new(11);
    for dh in [DhParameters::UR5E, DhParameters::UR5] {
        let (mut worst_regular, mut worst_near_singular) = (0.0f64, 0.0f64);
        for _ in 0..100_000 {
            let q = random_joints(&mut random);
            let pose = dh.forward(&q);
            let solutions = dh.inverse(&pose, q[5]);
            assert!(
                !solutions.is_empty(),
                "{dh:?}: no solution for the pose of {q:?}"
            );
            let near_singular = q[4].sin().abs() < 1e-3 || q[2].sin().abs() < 1e-3;
            for solution in solutions.as_slice() {
                let (position, rotation) = errors(&dh.forward(solution), &pose);
                let error = position.max(rotation);
                if near_singular {
                    worst_near_singular = worst_near_singular.max(error);
                } else {
                    worst_regular = worst_regular.max(error);
                }
            }
            if !near_singular {
                let found = solutions.as_slice().iter().any(|s| {
                    s.iter()
                        .zip(&q)
                        .all(|(a, b)| ((a - b) / TAU).round().mul_add(-TAU, a - b).abs() < 1e-6)
                });
                assert!(found, "{dh:?}: {q:?} is not among {solutions:?}");
            }
        }
        assert!(worst_regular < 1e-8, "{dh:?}: {worst_regular}");
        assert!(worst_near_singular < 1e-6, "{dh:?}: {worst_near_singular}");
    }
}

#[test]
fn the_nearest_solution_is_chosen_with_its_turn_nearest_the_current_joints() {
    let kinematics = Kinematics::new(DhParameters::UR5E);
    let q = [-0.3, -1.2, 1.4, -1.6, -1.2, 0.4];
    let pose = kinematics.forward(&q);
    // Near the same joints, a turn away on the base and wrist 3.
    let current = [-0.3 + TAU - 0.01, -1.2, 1.4, -1.6, -1.2, 0.4 - TAU];
    let chosen = kinematics.nearest(&pose, &current).expect("reachable");
    let expected = [-0.3 + TAU, -1.2, 1.4, -1.6, -1.2, 0.4 - TAU];
    for (c, e) in chosen.iter().zip(expected) {
        assert!((c - e).abs() < 1e-9, "{chosen:?} vs {expected:?}");
    }
    // Every solution of `solutions` reproduces the pose and is within the limits.
    let solutions = kinematics.solutions(&pose, &current);
    assert_eq!(solutions.len(), 8);
    for solution in &solutions {
        let (position, rotation) = errors(&kinematics.forward(solution), &pose);
        assert!(position < 1e-9 && rotation < 1e-9);
        assert!(solution[2].abs() <= PI && solution.iter().all(|q| q.abs() <= TAU));
    }
}

#[test]
fn limits_rule_out_solutions_and_a_pose_needing_more_is_an_error() {
    let q = [0.3, -1.2, 1.4, -1.6, -1.2, 0.4];
    let free = Kinematics::new(DhParameters::UR5E);
    let pose = free.forward(&q);
    let mut limits = free.limits;
    limits[2] = (0.0, PI); // elbow up only: half the solutions go
    let half = free.with_limits(limits);
    let solutions = half.solutions(&pose, &q);
    assert_eq!(solutions.len(), 4);
    assert!(solutions.iter().all(|s| s[2] >= 0.0));
    limits[0] = (2.0, 2.1); // no base angle of any solution
    let none = free.with_limits(limits);
    assert!(matches!(
        none.nearest(&pose, &q),
        Err(IkError::OutsideLimits { .. })
    ));
}

#[test]
fn unreachable_and_non_finite_poses_are_errors() {
    let kinematics = Kinematics::new(DhParameters::UR5E);
    let current = [0.0, -1.0, 1.0, -1.0, -1.0, 0.0];
    let far = pose_from_vector([1.5, 0.2, 0.3, PI, 0.0, 0.0]);
    let error = kinematics.nearest(&far, &current).unwrap_err();
    assert!(matches!(error, IkError::Unreachable { .. }));
    assert!(
        error.to_string().contains("out of the arm's reach"),
        "{error}"
    );
    // The wrist centre on the base axis: inside the shoulder offset's cylinder.
    let inside = pose_from_vector([0.0, 0.0, 0.3 + 0.0996, PI, 0.0, 0.0]);
    assert!(matches!(
        kinematics.nearest(&inside, &current),
        Err(IkError::Unreachable { .. })
    ));
    let nan = pose_from_vector([f64::NAN, 0.2, 0.3, PI, 0.0, 0.0]);
    assert!(matches!(
        kinematics.nearest(&nan, &current),
        Err(IkError::NotFinite { .. })
    ));
    let pose = kinematics.forward(&current);
    assert!(matches!(
        kinematics.nearest(&pose, &[f64::INFINITY; 6]),
        Err(IkError::NotFinite { .. })
    ));
    assert!(DhParameters::UR5E.inverse(&nan, 0.0).is_empty());
}

/// With wrist 2 at 0 the axes of wrist 1 and wrist 3 align: wrist 3 keeps its current angle and
/// wrist 1 takes up the rest.
#[test]
fn at_a_wrist_singularity_wrist_3_keeps_its_current_angle() {
    let kinematics = Kinematics::new(DhParameters::UR5E);
    let singular = [0.2, -1.3, 1.5, -1.2, 0.0, 0.7];
    let pose = kinematics.forward(&singular);
    let current = [0.25, -1.25, 1.45, -1.1, 0.05, 1.1];
    let chosen = kinematics
        .nearest(&pose, &current)
        .expect("a valid solution");
    assert!((chosen[5] - current[5]).abs() < 1e-12, "{chosen:?}");
    let (position, rotation) = errors(&kinematics.forward(&chosen), &pose);
    assert!(position < 1e-9 && rotation < 1e-9, "{position} {rotation}");
    assert!(chosen.iter().all(|q| q.is_finite()));
}

#[test]
fn the_tcp_offsets_forward_and_inverse_kinematics_alike() {
    let tcp = Isometry3::from_parts(
        Translation3::new(0.0, 0.0, 0.15),
        UnitQuaternion::identity(),
    );
    let kinematics = Kinematics::new(DhParameters::UR5).with_tcp(tcp);
    let q = [0.1, -1.0, 1.2, -1.7, -1.5, 0.3];
    let flange = DhParameters::UR5.forward(&q);
    let at = kinematics.forward(&q);
    let along = flange.rotation * Vector3::z();
    assert!((at.translation.vector - flange.translation.vector - 0.15 * along).norm() < 1e-12);
    let back = kinematics.nearest(&at, &q).expect("reachable");
    assert!(back.iter().zip(q).all(|(a, b)| (a - b).abs() < 1e-9));
}

#[test]
fn ur_pose_vectors_round_trip() {
    let mut random = SplitMix64::new(3);
    for _ in 0..1000 {
        let axis = Vector3::from_fn(|_, _| random.uniform(-1.0, 1.0)).normalize();
        let angle = random.uniform(0.0, PI);
        let vector = [
            0.1,
            -0.2,
            0.3,
            axis.x * angle,
            axis.y * angle,
            axis.z * angle,
        ];
        let back = pose_to_vector(&pose_from_vector(vector));
        for (a, b) in back.iter().zip(vector) {
            assert!((a - b).abs() < 1e-9, "{back:?} vs {vector:?}");
        }
    }
}
