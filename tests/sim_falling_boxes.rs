//! The falling-boxes example scene, used through the `yarok` facade as a downstream crate would:
//! the boxes come to rest on the floor, the arm reaches its target, and the camera sees them.

use std::sync::Arc;

use yarok::mjc::{Data, Model, RenderPreset, Renderer};

const SCENE: &str = include_str!("../examples/sim/falling_boxes.xml");

#[test]
fn boxes_settle_and_the_arm_reaches_its_target() {
    let model = Arc::new(Model::from_xml_str(SCENE).unwrap());
    let mut data = Data::new(&model).unwrap();
    data.set_ctrl(model.actuator("shoulder").unwrap(), 0.8);
    data.set_ctrl(model.actuator("elbow").unwrap(), -1.2);
    for _ in 0..(2.0 / model.timestep()) as usize {
        data.step();
    }
    data.forward();
    for (name, half_height) in [("box_red", 0.06), ("box_yellow", 0.05)] {
        let z = data.body_pose(model.body(name).unwrap()).pos[2];
        assert!(
            (z - half_height).abs() < 2e-3,
            "{name} rests at z = {z}, not on the floor"
        );
    }
    let elbow = data.sensor(model.sensor("elbow_angle").unwrap())[0];
    assert!(
        (elbow + 1.2).abs() < 0.02,
        "elbow at {elbow} rad, target -1.2"
    );
}

#[test]
fn the_overview_camera_sees_the_scene() {
    let model = Arc::new(Model::from_xml_str(SCENE).unwrap());
    let mut data = Data::new(&model).unwrap();
    data.forward();
    let mut renderer = Renderer::builder()
        .size(160, 120)
        .preset(RenderPreset::Fast)
        .build(&model)
        .unwrap();
    let (rgb, depth) = renderer
        .render(&mut data, model.camera("overview").unwrap())
        .unwrap();
    // The floor fills the bottom row, a few metres away; the sky above the horizon is far.
    let bottom = depth.get_pixel(80, 119)[0];
    assert!((1.0..4.0).contains(&bottom), "floor at {bottom} m");
    assert!(
        depth.get_pixel(80, 0)[0] > 10.0,
        "the top row looks past the floor"
    );
    let red = rgb
        .pixels()
        .filter(|p| p[0] > 150 && p[1] < 80 && p[2] < 80)
        .count();
    assert!(red > 20, "the red box is in view ({red} red pixels)");
}
