//! The component model end to end, with yarok's own environments: a component in `sim`, `mock`
//! and a user-defined environment; the environment check before anything starts; plugins that
//! read the simulation; stepping tick by tick; typed interface settings; the platform seed.

use std::cell::RefCell;
use std::rc::Rc;

use yarok::components::tactile::default_background;
use yarok::components::tactile::phong::{PhongModel, PhongParams};
use yarok::core::component::{Environment, MockBackend};
use yarok::mjc::SimBackend;
use yarok::prelude::*;

/// Replays a recording: a user-defined environment with a backend of yarok's.
struct Replay;
impl Environment for Replay {
    const NAME: &'static str = "replay";
    type Backend = MockBackend;
}

/// Its interface settings (`[interfaces."/lamp"]`).
#[derive(serde::Deserialize)]
#[serde(default)]
struct LampSettings {
    brightness: f64,
    label: String,
}

impl Default for LampSettings {
    fn default() -> Self {
        Self {
            brightness: 1.0,
            label: "lamp".into(),
        }
    }
}

/// A lamp on a hinge: in `sim` its angle comes from MuJoCo, in `mock` it is 0, in `replay` it is
/// the recorded 0.25.
#[derive(Clone)]
struct Lamp {
    angle: LampAngle,
    brightness: f64,
    label: String,
}

#[derive(Clone)]
enum LampAngle {
    Sim(Joint),
    Fixed(f64),
}

impl Lamp {
    fn angle(&self) -> f64 {
        match &self.angle {
            LampAngle::Sim(joint) => joint.position(),
            LampAngle::Fixed(angle) => *angle,
        }
    }
}

impl Component for Lamp {
    fn declaration() -> Declaration {
        Declaration::new("lamp").template(
            r#"<mujoco><worldbody><body name="arm" pos="0 0 1">
                 <joint name="hinge" axis="0 1 0"/>
                 <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
               </body></worldbody></mujoco>"#,
        )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>().add::<Replay>();
    }
}

impl Lamp {
    fn with_settings<E: Environment>(bind: &Bind<E>, angle: LampAngle) -> Result<Self, BindError> {
        let settings: LampSettings = bind.settings()?;
        Ok(Lamp {
            angle,
            brightness: settings.brightness,
            label: settings.label,
        })
    }
}

impl Interface<Sim> for Lamp {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let joint = bind.joint("hinge")?;
        Lamp::with_settings(bind, LampAngle::Sim(joint))
    }
}

impl Interface<Mock> for Lamp {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Lamp::with_settings(bind, LampAngle::Fixed(0.0))
    }
}

impl Interface<Replay> for Lamp {
    async fn bind(bind: &mut Bind<Replay>) -> Result<Self, BindError> {
        Lamp::with_settings(bind, LampAngle::Fixed(0.25))
    }
}

/// A lamp at `/lamp`.
struct Desk;
impl Component for Desk {
    fn declaration() -> Declaration {
        Declaration::new("desk")
            .uses::<Lamp>()
            .template(r#"<mujoco><worldbody><lamp name="lamp"/></worldbody></mujoco>"#)
    }
}

fn desk() -> yarok::core::runtime::PlatformBuilder {
    yarok::platform()
        .world::<Desk>()
        .backend::<Replay>(|_, _| Ok(MockBackend::new(0.01, false)))
}

/// The lamp's angle after 0.5 s in `environment`.
fn angle_in(environment: &str) -> f64 {
    let angle = Rc::new(RefCell::new(f64::NAN));
    let out = Rc::clone(&angle);
    desk()
        .environment(environment)
        .behaviour(move |pl| async move {
            let lamp: Lamp = pl.get("/lamp")?;
            pl.wait_seconds(0.5).await?;
            *out.borrow_mut() = lamp.angle();
            Ok(())
        })
        .run()
        .unwrap();
    angle.take()
}

#[test]
fn one_component_runs_in_sim_mock_and_a_user_defined_environment() {
    let swung = angle_in("sim");
    assert!(swung.abs() > 0.1, "gravity swings the lamp in sim: {swung}");
    assert_eq!(angle_in("mock"), 0.0);
    assert_eq!(angle_in("replay"), 0.25);
}

/// Two ropes and the printer: the ropes exist only in simulation, the printer on hardware too.
struct RopesAndPrinter;

impl Component for RopesAndPrinter {
    fn declaration() -> Declaration {
        Declaration::new("ropes_and_printer")
            .uses::<yarok::components::toys::Rope>()
            .uses::<yarok::components::robots::AnetA30>()
            .template(
                r#"<mujoco><worldbody>
                  <rope name="red"/><rope name="blue" pos="0.1 0 0.006"/>
                  <anet_a30 name="printer"/>
                </worldbody></mujoco>"#,
            )
    }
}

#[test]
fn env_real_on_a_world_of_sim_components_fails_before_binding_and_lists_them() {
    let error = yarok::platform()
        .world::<RopesAndPrinter>()
        .args(["--env", "real"].map(String::from))
        .unwrap()
        .behaviour(|_| async { panic!("nothing runs") })
        .build()
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "components cannot run in `real`: /red (Rope) supports sim, mock; /blue (Rope) \
         supports sim, mock"
    );
}

#[test]
fn a_plugin_reads_qpos_from_the_sim_backend_every_tick() {
    let seen = Rc::new(RefCell::new(Vec::new()));
    let (log, checked) = (Rc::clone(&seen), Rc::clone(&seen));
    desk()
        .plugin(move |world: &World<'_>| {
            let sim = world.backend::<SimBackend>().ok_or("not in sim")?;
            let hinge = sim.model().joint("lamp/hinge")?;
            // The clock has advanced to the step the plugin follows.
            assert_eq!(world.pl().time(), sim.data().time());
            log.borrow_mut()
                .push((world.pl().ticks(), sim.data().qpos(hinge)[0]));
            Ok(())
        })
        .behaviour(move |pl| async move {
            let lamp: Lamp = pl.get("/lamp")?;
            for _ in 0..5 {
                pl.tick().await?;
                // The plugin saw this tick's state: the angle the behaviour sees now.
                let last = checked.borrow().last().map(|(_, qpos)| *qpos);
                assert_eq!(last, Some(lamp.angle()));
            }
            Ok(())
        })
        .run()
        .unwrap();
    let seen = seen.borrow();
    assert_eq!(
        seen.iter().map(|(tick, _)| *tick).collect::<Vec<_>>(),
        [1, 2, 3, 4, 5]
    );
    assert!(
        seen.windows(2).all(|w| w[1].1.abs() > w[0].1.abs()),
        "the lamp falls further every tick: {seen:?}"
    );
}

#[test]
fn platform_step_advances_one_tick_so_a_test_can_assert_between_ticks() {
    let mut platform = desk()
        .behaviour(|pl| async move {
            pl.wait_seconds(0.1).await?;
            Ok(())
        })
        .build()
        .unwrap();
    let timestep = platform.pl().timestep();
    let mut angles = Vec::new();
    while platform.step().unwrap() {
        let lamp: Lamp = platform.pl().get("/lamp").unwrap();
        assert!((platform.pl().time() - platform.pl().ticks() as f64 * timestep).abs() < 1e-9);
        angles.push(lamp.angle());
    }
    assert_eq!(platform.pl().ticks(), (0.1 / timestep).round() as u64);
    assert_eq!(angles.len() + 1, platform.pl().ticks() as usize);
    assert!(angles.windows(2).all(|w| w[1].abs() > w[0].abs()));
    assert!(!platform.step().unwrap(), "an ended platform stays ended");
}

#[test]
fn interface_settings_are_typed_and_checked() {
    let label = Rc::new(RefCell::new(String::new()));
    let out = Rc::clone(&label);
    desk()
        .set("interfaces/lamp/brightness=0.5")
        .unwrap()
        .set("interfaces/lamp/label=desk lamp")
        .unwrap()
        .behaviour(move |pl| async move {
            let lamp: Lamp = pl.get("/lamp")?;
            assert_eq!(lamp.brightness, 0.5);
            *out.borrow_mut() = lamp.label.clone();
            Ok(())
        })
        .run()
        .unwrap();
    assert_eq!(*label.borrow(), "desk lamp");

    let error = |assignment: &str| {
        desk()
            .set(assignment)
            .unwrap()
            .behaviour(|_| async { Ok(()) })
            .run()
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        error("interfaces/lamp/brigthness=0.5"),
        "component /lamp: --set interfaces/lamp/brigthness=0.5: no setting `brigthness` (it has \
         brightness, label); did you mean `brightness`?"
    );
    assert_eq!(
        error("interfaces/lamp/brightness=bright"),
        "component /lamp: --set interfaces/lamp/brightness=bright: `brightness` expects a number, \
         got \"bright\""
    );
}

/// A gel whose texture noise is drawn at bind time from the component's seed.
#[derive(Clone)]
struct Gel {
    image: Rc<Vec<u8>>,
}

impl Component for Gel {
    fn declaration() -> Declaration {
        Declaration::new("gel").template("<mujoco/>")
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Mock>();
    }
}

impl Interface<Mock> for Gel {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        let (width, height) = (240, 320);
        let params = PhongParams {
            seed: bind.seed(),
            texture_sigma: 1e-3,
            ..PhongParams::digit()
        };
        let depth = vec![1.0_f32; width * height];
        let image = PhongModel::new(params)
            .render(&depth, width, &default_background(width, height))
            .map_err(|e| bind.error(e))?;
        Ok(Gel {
            image: Rc::new(image),
        })
    }
}

/// Two gels, `/left` and `/right`.
struct Pair;
impl Component for Pair {
    fn declaration() -> Declaration {
        Declaration::new("pair").uses::<Gel>().template(
            r#"<mujoco><worldbody><gel name="left"/><gel name="right"/></worldbody></mujoco>"#,
        )
    }
}

/// The two gels' images with `[platform] seed = seed`.
fn textures(seed: u64) -> (Vec<u8>, Vec<u8>) {
    let images = Rc::new(RefCell::new((Vec::new(), Vec::new())));
    let out = Rc::clone(&images);
    yarok::platform()
        .world::<Pair>()
        .environment("mock")
        .set(&format!("platform/seed={seed}"))
        .unwrap()
        .behaviour(move |pl| async move {
            let (left, right): (Gel, Gel) = (pl.get("/left")?, pl.get("/right")?);
            *out.borrow_mut() = (left.image.to_vec(), right.image.to_vec());
            Ok(())
        })
        .run()
        .unwrap();
    images.take()
}

#[test]
fn the_platform_seed_reaches_every_component_that_draws_random_numbers() {
    let (left, right) = textures(1);
    assert_eq!(
        textures(1),
        (left.clone(), right.clone()),
        "same seed, same noise"
    );
    assert_ne!(left, right, "two components draw different noise");
    let (other_left, _) = textures(2);
    assert_ne!(left, other_left, "another seed, other noise");
}
