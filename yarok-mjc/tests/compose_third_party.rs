//! Unmodified third-party files compose: angles in another unit than the world's are converted,
//! and several top-level `<default>` sections (one per included file) stay one class each.

use std::path::PathBuf;

use yarok_core::component::{Component, Declaration};
use yarok_core::compose::compose;
use yarok_mjc::{Model, Pose};

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/degrees")
        .join(name)
}

struct DegreeArm;
impl Component for DegreeArm {
    fn declaration() -> Declaration {
        Declaration::new("degree-arm").template_file(fixture("arm.xml"))
    }
}

/// A world in radians holding the arm (written in degrees) twice.
struct RadianCell;
impl Component for RadianCell {
    fn declaration() -> Declaration {
        Declaration::new("cell").uses::<DegreeArm>().template(
            r#"<mujoco>
                 <compiler angle="radian"/>
                 <worldbody>
                   <body name="left_mount" pos="0 0.5 0" euler="0 0 1.5707963267948966">
                     <degree-arm name="left"/>
                   </body>
                   <degree-arm name="right"/>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

fn same_pose(a: Pose, b: Pose) -> bool {
    let dot: f64 = a.quat.iter().zip(b.quat).map(|(x, y)| x * y).sum();
    a.pos.iter().zip(b.pos).all(|(x, y)| (x - y).abs() < 1e-12) && (dot.abs() - 1.0).abs() < 1e-12
}

#[test]
fn a_component_in_degrees_compiles_in_a_radian_world_as_it_does_alone() {
    let alone = Model::from_file(fixture("arm.xml")).unwrap();
    let composed = Model::from_composition(&compose::<RadianCell>().unwrap()).unwrap();
    for arm in ["left", "right"] {
        for body in ["base", "upper", "fore"] {
            assert!(
                same_pose(
                    alone.body_local_pose(alone.body(body).unwrap()),
                    composed.body_local_pose(composed.body(&format!("{arm}/{body}")).unwrap())
                ),
                "{arm}/{body}"
            );
        }
        for joint in ["shoulder", "elbow", "slide"] {
            let expected = alone.joint_range(alone.joint(joint).unwrap());
            let got = composed.joint_range(composed.joint(&format!("{arm}/{joint}")).unwrap());
            let (expected, got) = (expected.unwrap(), got.unwrap());
            assert!(
                (expected[0] - got[0]).abs() < 1e-12 && (expected[1] - got[1]).abs() < 1e-12,
                "{arm}/{joint}: {expected:?} vs {got:?}"
            );
        }
    }
    let shoulder = alone.joint_range(alone.joint("shoulder").unwrap()).unwrap();
    assert!(
        (shoulder[1] - 120f64.to_radians()).abs() < 1e-12,
        "{shoulder:?}"
    );
    let slide = alone.joint_range(alone.joint("slide").unwrap()).unwrap();
    assert_eq!(slide, [-0.1, 0.2], "slide joints are not angles");
    let elbow = alone.joint_range(alone.joint("elbow").unwrap()).unwrap();
    assert!(
        (elbow[1] - 170f64.to_radians()).abs() < 1e-12,
        "the wrist class's range"
    );
}

/// A file written in radians that does not say so, wrapped as it is.
struct SilentHinge;
impl Component for SilentHinge {
    fn declaration() -> Declaration {
        Declaration::new("silent-hinge").mjcf_file(
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/no_unit/hinge.xml"),
        )
    }
}

/// The same file with its angle unit stated, without editing it: a component that extends it
/// and sets only `<compiler angle>`.
struct RadianHinge;
impl Component for RadianHinge {
    fn declaration() -> Declaration {
        Declaration::new("radian-hinge")
            .extends::<SilentHinge>()
            .template(r#"<mujoco><compiler angle="radian"/></mujoco>"#)
    }
}

#[test]
fn a_wrapped_files_angle_unit_is_stated_by_extending_it() {
    let range = |model: &Model| model.joint_range(model.joint("hinge").unwrap()).unwrap();
    let silent = Model::from_composition(&compose::<SilentHinge>().unwrap()).unwrap();
    assert!(
        (range(&silent)[1] - 1.5f64.to_radians()).abs() < 1e-12,
        "read as MuJoCo reads it, in degrees: {:?}",
        range(&silent)
    );
    let stated = Model::from_composition(&compose::<RadianHinge>().unwrap()).unwrap();
    assert_eq!(range(&stated), [-1.5, 1.5]);
}
