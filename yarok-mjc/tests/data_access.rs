//! Names to ids, and reading and writing the simulation state through them.

use std::sync::Arc;

use yarok_mjc::{Data, Model, ModelError, ObjectKind};

const SCENE: &str = r#"
<mujoco>
  <worldbody>
    <camera name="eye" pos="0 0 3" euler="90 0 0"/>
    <site name="anchor" pos="0 0 1"/>
    <body name="stand" pos="0 0 1">
      <site name="imu"/>
      <body name="link">
        <joint name="hinge" axis="0 1 0"/>
        <geom name="rod" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <site name="tip" pos="0.3 0 0"/>
      </body>
    </body>
    <body name="ball" pos="1 0 1">
      <freejoint name="ball_free"/>
      <geom name="ball_geom" size="0.05"/>
    </body>
  </worldbody>
  <tendon><spatial name="cable"><site site="anchor"/><site site="tip"/></spatial></tendon>
  <actuator><motor name="torque" joint="hinge"/></actuator>
  <sensor>
    <accelerometer name="acc" site="imu"/>
    <jointpos name="angle" joint="hinge"/>
    <framepos name="tip_pos" objtype="site" objname="tip"/>
  </sensor>
</mujoco>"#;

fn setup() -> (Arc<Model>, Data) {
    let model = Arc::new(Model::from_xml_str(SCENE).unwrap());
    let data = Data::new(&model).unwrap();
    (model, data)
}

#[test]
fn every_kind_of_name_resolves_to_its_index() {
    let (model, _) = setup();
    assert_eq!(model.body("stand").unwrap().index(), 1);
    assert_eq!(model.body("ball").unwrap().index(), 3);
    assert_eq!(model.joint("ball_free").unwrap().index(), 1);
    assert_eq!(model.geom("ball_geom").unwrap().index(), 1);
    assert_eq!(model.site("tip").unwrap().index(), 2);
    assert_eq!(model.camera("eye").unwrap().index(), 0);
    assert_eq!(model.actuator("torque").unwrap().index(), 0);
    assert_eq!(model.sensor("tip_pos").unwrap().index(), 2);
    assert_eq!(model.tendon("cable").unwrap().index(), 0);
    assert_eq!(model.count(ObjectKind::Sensor), 3);
}

#[test]
fn a_missing_name_is_an_error_naming_kind_and_name() {
    let (model, _) = setup();
    let error = model.joint("elbow").unwrap_err();
    assert_eq!(
        error,
        ModelError::UnknownName {
            kind: ObjectKind::Joint,
            name: "elbow".into()
        }
    );
    assert_eq!(error.to_string(), r#"the model has no joint named "elbow""#);
    // A name of another kind is not found either.
    assert!(model.body("hinge").is_err());
    assert!(model.sensor("").is_err());
}

#[test]
fn sensors_are_read_at_their_address_with_their_dimension() {
    let (model, mut data) = setup();
    let hinge = model.joint("hinge").unwrap();
    data.qpos_mut(hinge)[0] = 0.3;
    data.forward();

    let acc = data.sensor(model.sensor("acc").unwrap());
    let angle = data.sensor(model.sensor("angle").unwrap());
    let tip = data.sensor(model.sensor("tip_pos").unwrap());
    assert_eq!(acc.len(), 3);
    assert_eq!(angle, &[0.3]);
    assert!(
        (acc[2] - 9.81).abs() < 1e-9,
        "a welded accelerometer feels gravity: {acc:?}"
    );
    // Rotating +0.3 rad about +y tips the rod's end downwards.
    let expected = [0.3 * 0.3f64.cos(), 0.0, 1.0 - 0.3 * 0.3f64.sin()];
    for (got, want) in tip.iter().zip(expected) {
        assert!((got - want).abs() < 1e-12, "{tip:?} vs {expected:?}");
    }
}

#[test]
fn free_joint_has_seven_positions_and_six_velocities() {
    let (model, mut data) = setup();
    let free = model.joint("ball_free").unwrap();
    assert_eq!(data.qpos(free), &[1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0]);
    assert_eq!(data.qvel(free).len(), 6);
    data.qvel_mut(free)[0] = 2.0;
    data.step();
    assert!(data.qpos(free)[0] > 1.0);
    data.forward();
    let pose = data.body_pose(model.body("ball").unwrap());
    assert_eq!(pose.pos[0], data.qpos(free)[0]);
}

#[test]
fn cameras_are_listed_with_their_names_and_poses() {
    let (model, mut data) = setup();
    let cameras: Vec<_> = model.cameras().collect();
    assert_eq!(cameras, vec![model.camera("eye").unwrap()]);
    assert_eq!(model.camera_name(cameras[0]).as_deref(), Some("eye"));
    data.forward();
    let pose = data.camera_pose(cameras[0]);
    assert_eq!(pose.pos, [0.0, 0.0, 3.0]);
    // Turned 90° about x: w = x = cos 45°.
    let half = std::f64::consts::FRAC_1_SQRT_2;
    for (got, want) in pose.quat.iter().zip([half, half, 0.0, 0.0]) {
        assert!((got - want).abs() < 1e-9, "{:?}", pose.quat);
    }
}

#[test]
fn actuators_are_listed_in_the_order_of_the_controls_with_their_names() {
    let (model, mut data) = setup();
    let actuators: Vec<_> = model.actuators().collect();
    assert_eq!(actuators, vec![model.actuator("torque").unwrap()]);
    assert_eq!(model.actuator_name(actuators[0]).as_deref(), Some("torque"));
    data.set_ctrl(actuators[0], 0.5);
    assert_eq!(data.ctrl()[actuators[0].index()], 0.5);
}

#[test]
fn control_moves_the_joint_and_reset_restores_it() {
    let (model, mut data) = setup();
    let hinge = model.joint("hinge").unwrap();
    data.set_ctrl(model.actuator("torque").unwrap(), 1.0);
    assert_eq!(data.ctrl(), &[1.0]);
    for _ in 0..100 {
        data.step();
    }
    assert!((data.time() - 100.0 * model.timestep()).abs() < 1e-12);
    assert_ne!(data.qpos(hinge)[0], 0.0);
    data.reset();
    assert_eq!(data.time(), 0.0);
    assert_eq!(data.qpos(hinge), &[0.0]);
    assert_eq!(data.ctrl(), &[0.0]);
}

#[test]
fn stepping_is_deterministic() {
    let run = || {
        let (model, mut data) = setup();
        data.set_ctrl(model.actuator("torque").unwrap(), 0.7);
        for _ in 0..500 {
            data.step();
        }
        data.qpos(model.joint("ball_free").unwrap()).to_vec()
    };
    assert_eq!(run(), run());
}

#[test]
#[should_panic(expected = "joint id 0 used with a model it was not resolved in")]
fn an_id_from_another_model_is_refused() {
    let (_, data) = setup();
    let other = Model::from_xml_str(
        r#"<mujoco><worldbody><body><joint name="j"/><geom size="1"/></body></worldbody></mujoco>"#,
    )
    .unwrap();
    let _ = data.qpos(other.joint("j").unwrap());
}

#[test]
fn models_and_data_move_across_threads() {
    let (model, mut data) = setup();
    let handle = std::thread::spawn(move || {
        data.step();
        data.time()
    });
    assert_eq!(handle.join().unwrap(), model.timestep());
}

#[test]
fn mujoco_warnings_reach_tracing() {
    use std::sync::Mutex;

    #[derive(Clone, Default)]
    struct Capture(Arc<Mutex<Vec<u8>>>);
    impl std::io::Write for Capture {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(bytes);
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    let capture = Capture::default();
    let writer = capture.clone();
    let subscriber = tracing_subscriber::fmt()
        .with_writer(move || writer.clone())
        .with_ansi(false)
        .finish();
    tracing::subscriber::with_default(subscriber, || {
        let (model, mut data) = setup();
        data.qvel_mut(model.joint("hinge").unwrap())[0] = f64::NAN;
        data.step();
    });
    let log = String::from_utf8(capture.0.lock().unwrap().clone()).unwrap();
    assert!(log.contains("WARN") && log.contains("mujoco"), "{log}");
    assert!(log.contains("QVEL"), "{log}");
}
