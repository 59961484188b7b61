//! Two copies of an arm carrying a gripper in one world: every kind of name and reference
//! (default classes, meshes in a subfolder, sites, sensors by `objname`, a tendon, an equality
//! constraint, a contact exclusion, keyframes) resolves in MuJoCo, per copy.

use std::path::PathBuf;
use std::sync::Arc;

use yarok_core::component::{Component, Declaration, NameKind};
use yarok_core::compose::compose;
use yarok_mjc::{Data, Model, ObjectKind};

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/arm")
}

struct Arm;
impl Component for Arm {
    fn declaration() -> Declaration {
        Declaration::new("arm")
            .default("link_radius", 0.03)
            .template_file(fixtures().join("arm.xml"))
    }
}

struct Gripper;
impl Component for Gripper {
    fn declaration() -> Declaration {
        Declaration::new("gripper").template_file(fixtures().join("gripper.xml"))
    }
}

/// An arm with a gripper on its flange: the gripper is `<path>/arm/gripper`.
struct ArmWithGripper;
impl Component for ArmWithGripper {
    fn declaration() -> Declaration {
        Declaration::new("arm_with_gripper")
            .uses::<Arm>()
            .uses::<Gripper>()
            .default("radius", 0.03)
            .template(
                r#"<mujoco>
                 <compiler angle="radian"/>
                 <worldbody>
                   <arm name="arm" link_radius="{radius}">
                     <gripper name="gripper" parent="flange"/>
                   </arm>
                 </worldbody>
               </mujoco>"#,
            )
    }
}

struct TwoArms;
impl Component for TwoArms {
    fn declaration() -> Declaration {
        Declaration::new("two_arms").uses::<ArmWithGripper>().template(
            r#"<mujoco model="two arms">
                 <compiler angle="radian"/>
                 <worldbody>
                   <geom name="floor" type="plane" size="2 2 0.1"/>
                   <body name="left_mount" pos="-0.5 0 0"><arm_with_gripper name="left"/></body>
                   <body name="right_mount" pos="0.5 0 0"><arm_with_gripper name="right" radius="0.02"/></body>
                 </worldbody>
                 <sensor>
                   <framepos name="right_pad" objtype="site" objname="right/arm/gripper/right_pad"/>
                 </sensor>
                 <equality>
                   <weld name="glue" body1="left/arm/base" body2="right/arm/base" active="false"/>
                 </equality>
                 <keyframe>
                   <key name="start" from="left/arm/home right/arm/home right/arm/gripper/open"
                        time="1.5"/>
                 </keyframe>
               </mujoco>"#,
        )
    }
}

#[test]
fn two_arm_and_gripper_copies_compile_with_every_reference_resolved() {
    let world = compose::<TwoArms>().unwrap();
    let paths: Vec<&str> = world.instances.iter().map(|i| i.path.as_str()).collect();
    assert_eq!(
        paths,
        [
            "/",
            "/left",
            "/left/arm",
            "/left/arm/gripper",
            "/right",
            "/right/arm",
            "/right/arm/gripper"
        ]
    );
    assert_eq!(world.assets, [fixtures().join("meshes/base.obj")]);

    let model = Arc::new(Model::from_composition(&world).unwrap());
    for side in ["left", "right"] {
        for body in [
            "arm/base",
            "arm/upper",
            "arm/fore",
            "arm/flange",
            "arm/gripper/palm",
            "arm/gripper/left",
        ] {
            model.body(&format!("{side}/{body}")).unwrap();
        }
        for joint in [
            "arm/shoulder",
            "arm/elbow",
            "arm/gripper/left_slide",
            "arm/gripper/right_slide",
        ] {
            model.joint(&format!("{side}/{joint}")).unwrap();
        }
        model.tendon(&format!("{side}/arm/gripper/split")).unwrap();
        model
            .actuator(&format!("{side}/arm/gripper/close"))
            .unwrap();
        model.sensor(&format!("{side}/arm/wrist")).unwrap();
    }
    assert_eq!(model.count(ObjectKind::Body), 1 + 2 + 2 * 7);
    assert_eq!(model.count(ObjectKind::Actuator), 6);
    assert_eq!(model.count(ObjectKind::Sensor), 2 * 4 + 1);
    let m = model.ffi();
    assert_eq!(
        (m.nmesh, m.nmat, m.ntendon, m.neq, m.nexclude),
        (2, 2, 2, 3, 2)
    );

    // The gripper hangs from the flange of its own arm.
    let palm = model.body("left/arm/gripper/palm").unwrap();
    assert_eq!(
        model.body_parent(palm),
        model.body("left/arm/flange").unwrap()
    );

    // Default classes apply per copy: the right arm's links are thinner.
    let radius = |name: &str| model.geom_size(model.geom(name).unwrap())[0];
    assert_eq!(radius("left/arm/fore_geom"), 0.03);
    assert_eq!(radius("right/arm/fore_geom"), 0.02);

    // Sensors by objname point at their own copy's site.
    let mut data = Data::new(&model).unwrap();
    data.forward();
    let left_wrist = data
        .sensor(model.sensor("left/arm/wrist").unwrap())
        .to_vec();
    let right_wrist = data
        .sensor(model.sensor("right/arm/wrist").unwrap())
        .to_vec();
    assert!(
        (left_wrist[0] + 0.5).abs() < 1e-9 && (right_wrist[0] - 0.5).abs() < 1e-9,
        "{left_wrist:?} {right_wrist:?}"
    );
    assert!((left_wrist[2] - 0.65).abs() < 1e-9);

    // Name maps give each component its own names.
    let gripper = world.instance("/right/arm/gripper").unwrap();
    assert_eq!(
        gripper.names.get(NameKind::Tendon, "split"),
        Some("right/arm/gripper/split")
    );
    assert_eq!(
        gripper.names.get(NameKind::Class, "finger"),
        Some("right/arm/gripper/finger")
    );
}

#[test]
fn component_keyframes_set_only_their_components_state() {
    let model = Arc::new(Model::from_composition(&compose::<TwoArms>().unwrap()).unwrap());
    let mut data = Data::new(&model).unwrap();
    data.reset_to_keyframe(model.keyframe("left/arm/home").unwrap());
    assert_eq!(data.qpos(model.joint("left/arm/shoulder").unwrap()), &[0.3]);
    assert_eq!(data.qpos(model.joint("left/arm/elbow").unwrap()), &[-0.6]);
    assert_eq!(data.qpos(model.joint("right/arm/elbow").unwrap()), &[0.0]);
    assert_eq!(
        data.qpos(model.joint("left/arm/gripper/left_slide").unwrap()),
        &[0.0]
    );
    assert_eq!(
        data.ctrl()[model.actuator("left/arm/elbow").unwrap().index()],
        -0.6
    );

    data.reset_to_keyframe(model.keyframe("right/arm/gripper/open").unwrap());
    assert_eq!(
        data.qpos(model.joint("right/arm/gripper/right_slide").unwrap()),
        &[0.04]
    );
    assert_eq!(
        data.qpos(model.joint("left/arm/gripper/right_slide").unwrap()),
        &[0.0]
    );
    assert_eq!(
        data.ctrl()[model.actuator("right/arm/gripper/close").unwrap().index()],
        0.04
    );
    assert_eq!(data.ctrl().iter().filter(|c| **c != 0.0).count(), 1);
}

/// A world keyframe combines its components' keyframes by name: each component's part from its
/// own keyframe, with no index arithmetic.
#[test]
fn a_world_keyframe_combines_component_keyframes() {
    let model = Arc::new(Model::from_composition(&compose::<TwoArms>().unwrap()).unwrap());
    let mut data = Data::new(&model).unwrap();
    data.reset_to_keyframe(model.keyframe("start").unwrap());
    for arm in ["left", "right"] {
        assert_eq!(
            data.qpos(model.joint(&format!("{arm}/arm/shoulder")).unwrap()),
            &[0.3]
        );
        assert_eq!(
            data.qpos(model.joint(&format!("{arm}/arm/elbow")).unwrap()),
            &[-0.6]
        );
    }
    let slide = |arm: &str| {
        data.qpos(
            model
                .joint(&format!("{arm}/arm/gripper/right_slide"))
                .unwrap(),
        )[0]
    };
    assert_eq!((slide("left"), slide("right")), (0.0, 0.04));
    let close = |arm: &str| {
        data.ctrl()[model
            .actuator(&format!("{arm}/arm/gripper/close"))
            .unwrap()
            .index()]
    };
    assert_eq!((close("left"), close("right")), (0.0, 0.04));
    assert_eq!(
        data.ctrl()[model.actuator("right/arm/shoulder").unwrap().index()],
        0.3
    );
    assert_eq!(data.time(), 1.5);
}

struct Misnamed;
impl Component for Misnamed {
    fn declaration() -> Declaration {
        Declaration::new("misnamed")
            .uses::<ArmWithGripper>()
            .template(
                r#"<mujoco><compiler angle="radian"/>
                 <worldbody><arm_with_gripper name="left"/></worldbody>
                 <keyframe><key name="start" from="left/arm/hoem"/></keyframe>
               </mujoco>"#,
            )
    }
}

#[test]
fn combining_an_unknown_keyframe_is_an_error_with_a_suggestion() {
    let error = Model::from_composition(&compose::<Misnamed>().unwrap()).unwrap_err();
    assert_eq!(
        error.to_string(),
        "component /: keyframe \"start\": `from` names keyframe \"left/arm/hoem\", which the world does not have; did you mean `left/arm/home`?"
    );
}
