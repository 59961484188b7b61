//! MuJoCo Menagerie's UR5e and Robotiq 2F-85, each wrapped as it is with
//! `Declaration::mjcf_file`, in `PickAndPlaceWorld`'s layout: the gripper on the arm's
//! `attachment_site`, the arm's TCP at the gripper's pinch point.

use std::path::PathBuf;
use std::sync::OnceLock;

use yarok::components::grippers::{GripperNames, Robotiq2f85};
use yarok::components::robots::ur::{Arm, ArmConfig, ArmNames, MeasuredKinematics};
use yarok::components::toys::{Block, Spot};
use yarok::mjc::Sim;
use yarok::nalgebra::Isometry3;
use yarok::prelude::*;

/// The folder of MuJoCo Menagerie (holding `universal_robots_ur5e/` and `robotiq_2f85/`),
/// set before the world is built.
pub(crate) static MENAGERIE: OnceLock<PathBuf> = OnceLock::new();

/// Where the arm starts, as `PickAndPlaceWorld`'s does.
pub(crate) const START: [f64; 6] = [0.0, -1.9, 1.9, -1.57, -1.57, 0.0];

/// A file of Menagerie's.
fn menagerie(file: &str) -> PathBuf {
    MENAGERIE.get().cloned().unwrap_or_default().join(file)
}

/// Menagerie's `universal_robots_ur5e/ur5e.xml`: its kinematics measured from the model, its
/// TCP at the pinch point of the 2F-85 mounted on its attachment site (the 2F-85's base mount
/// 7 mm, base 3.8 mm and pinch 145 mm along the flange's z), starting as `PickAndPlaceWorld`'s
/// arm does.
#[derive(Clone, Debug)]
pub(crate) struct MenagerieUr5e(pub(crate) Arm);

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
        let pinch = Isometry3::translation(0.0, 0.0, 0.007 + 0.0038 + 0.145);
        let config = ArmConfig {
            kinematics: measured
                .kinematics
                .with_tcp(measured.kinematics.tcp * pinch),
            names: ArmNames::MENAGERIE,
            start: Some(START),
        };
        Arm::bind_sim(bind, config).map(MenagerieUr5e)
    }
}

/// Menagerie's `robotiq_2f85/2f85.xml`, driven through its own servo by the bundled
/// [`Robotiq2f85`].
#[derive(Clone, Debug)]
pub(crate) struct Menagerie2f85(pub(crate) Robotiq2f85);

impl Component for Menagerie2f85 {
    fn declaration() -> Declaration {
        Declaration::new("menagerie_2f85").mjcf_file(menagerie("robotiq_2f85/2f85.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for Menagerie2f85 {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Robotiq2f85::bind_sim(bind, &GripperNames::MENAGERIE_2F85).map(Menagerie2f85)
    }
}

/// `PickAndPlaceWorld`'s layout (a stand, a table 0.4 m high, three blocks and a target spot)
/// with Menagerie's arm and gripper.
pub(crate) struct MenagerieWorld;

impl Component for MenagerieWorld {
    fn declaration() -> Declaration {
        Declaration::new("menagerie_world")
            .uses::<MenagerieUr5e>()
            .uses::<Menagerie2f85>()
            .uses::<Block>()
            .uses::<Spot>()
            .template(
                r#"<mujoco>
                  <worldbody>
                    <light pos="0 0 3" dir="0 0 -1"/>
                    <geom name="floor" type="plane" size="2 2 0.1"/>
                    <geom name="stand" type="box" size="0.12 0.12 0.2" pos="0 0 0.2"/>
                    <geom name="table" type="box" size="0.4 0.6 0.02" pos="0.52 0 0.38"/>
                    <body name="mount" pos="0 0 0.4">
                      <menagerie_ur5e name="arm">
                        <menagerie_2f85 name="gripper" parent="attachment_site"/>
                      </menagerie_ur5e>
                    </body>
                    <block name="large" size="0.05" pos="{[0.5, -0.25, 0.425]}"/>
                    <block name="medium" size="0.04" pos="{[0.62, 0.02, 0.42]}"/>
                    <block name="small" size="0.03" pos="{[0.45, 0.12, 0.415]}"/>
                    <spot name="target" pos="{[0.42, 0.38, 0.4005]}"/>
                  </worldbody>
                </mujoco>"#,
            )
    }
}
