//! Composed worlds compile in MuJoCo: the tumble tower settles into a standing tower, and a
//! wrapped on-disk model used twice resolves its assets and names.

use std::path::PathBuf;
use std::sync::Arc;

use yarok::components::worlds::TowerWorld;
use yarok::core::component::{Component, Declaration};
use yarok::core::compose::compose;
use yarok::mjc::{Data, Model, ObjectKind};

#[test]
fn the_tumble_tower_compiles_and_stands() {
    let model = Arc::new(Model::from_composition(&compose::<TowerWorld>().unwrap()).unwrap());
    assert_eq!(model.count(ObjectKind::Body), 1 + 24);
    assert_eq!(model.nq(), 24 * 7);
    let mut data = Data::new(&model).unwrap();
    let top = model.body("tower/block_7_1").unwrap();
    data.forward();
    let start = data.body_pose(top).pos;
    for _ in 0..500 {
        data.step();
    }
    data.forward();
    let end = data.body_pose(top).pos;
    // The layers start 5 mm apart and settle onto each other; the top block stays above the rest.
    let settled = start[2] - 7.0 * 0.005;
    assert!(
        (end[2] - settled).abs() < 0.01,
        "the top block settles: {start:?} → {end:?}"
    );
    assert!(
        (end[0] - start[0]).hypot(end[1] - start[1]) < 0.01,
        "the tower does not fall: {start:?} → {end:?}"
    );
}

fn robot_file() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("yarok-core/tests/fixtures/robot/robot.xml")
}

struct Robot;
impl Component for Robot {
    fn declaration() -> Declaration {
        Declaration::new("robot").mjcf_file(robot_file())
    }
}

struct TwoRobots;
impl Component for TwoRobots {
    fn declaration() -> Declaration {
        Declaration::new("two_robots").uses::<Robot>().template(
            r#"<mujoco><compiler angle="radian"/><worldbody>
                 <robot name="a"/><body name="b_mount" pos="1 0 0"><robot name="b"/></body>
               </worldbody></mujoco>"#,
        )
    }
}

#[test]
fn a_wrapped_model_used_twice_compiles() {
    let model = Model::from_composition(&compose::<TwoRobots>().unwrap()).unwrap();
    for prefix in ["a", "b"] {
        model.body(&format!("{prefix}/link")).unwrap();
        model.joint(&format!("{prefix}/hinge")).unwrap();
    }
    let m = model.ffi();
    assert_eq!((m.nmesh, m.ntex, m.nmat), (2, 2, 2));
}
