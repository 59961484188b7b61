//! Components bound per environment, injection, plugins, and layered configuration.

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use yarok_core::BoxError;
use yarok_core::component::{
    Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, Mock, MockBackend,
    NameKind,
};
use yarok_core::config::RunConfig;
use yarok_core::runtime::{Platform, PlatformBuilder, Plugin, RuntimeError, World};

/// A stand-in for the simulator, so that these tests need no MuJoCo.
struct Sim;
impl Environment for Sim {
    const NAME: &'static str = "sim";
    type Backend = MockBackend;
}

/// A stand-in for hardware.
struct Real;
impl Environment for Real {
    const NAME: &'static str = "real";
    type Backend = MockBackend;
}

thread_local! {
    /// The order interfaces stepped in, by path (each test runs on its own thread).
    static STEPS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// A joint with a motor; its handle counts ticks and knows its resolved joint name.
#[derive(Clone)]
struct Motor {
    joint: String,
    speed: f64,
    ticks: Rc<Cell<u64>>,
}

/// The motor's config.
#[derive(serde::Serialize, serde::Deserialize)]
struct MotorConfig {
    speed: f64,
}

impl Component for Motor {
    fn declaration() -> Declaration {
        Declaration::new("motor")
            .config(MotorConfig { speed: 1.0 })
            .template(r#"<mujoco><worldbody><body name="rotor"><joint name="axle"/></body></worldbody></mujoco>"#)
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>();
    }
}

impl Motor {
    fn bind<E: Environment>(bind: &mut Bind<E>) -> Result<Self, BindError> {
        let MotorConfig { speed } = bind.config()?;
        let ticks = Rc::new(Cell::new(0));
        let counter = Rc::clone(&ticks);
        let path = bind.path().to_owned();
        bind.on_tick(move || {
            counter.set(counter.get() + 1);
            STEPS.with(|s| s.borrow_mut().push(path.clone()));
            Ok(())
        });
        Ok(Motor {
            joint: bind.name(NameKind::Joint, "axle")?.to_owned(),
            speed,
            ticks,
        })
    }
}

impl Interface<Sim> for Motor {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Motor::bind(bind)
    }
}

impl Interface<Mock> for Motor {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Motor::bind(bind)
    }
}

/// Two motors; its handle reaches its children through `Bind::child`.
#[derive(Clone)]
struct Car {
    left: Motor,
    right: Motor,
}

impl Component for Car {
    fn declaration() -> Declaration {
        Declaration::new("car").uses::<Motor>().template(
            r#"<mujoco><worldbody><body name="chassis">
                 <motor name="left"/><motor name="right" speed="2"/>
               </body></worldbody></mujoco>"#,
        )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>();
    }
}

impl Interface<Sim> for Car {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Car::bind(bind)
    }
}

impl Interface<Mock> for Car {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Car::bind(bind)
    }
}

impl Car {
    fn bind<E: Environment>(bind: &mut Bind<E>) -> Result<Self, BindError> {
        let path = bind.path().to_owned();
        bind.on_tick(move || {
            STEPS.with(|s| s.borrow_mut().push(path.clone()));
            Ok(())
        });
        Ok(Car {
            left: bind.child("left")?,
            right: bind.child("right")?,
        })
    }
}

#[derive(Clone)]
struct Garage;
impl Component for Garage {
    fn declaration() -> Declaration {
        Declaration::new("garage")
            .uses::<Car>()
            .template("<mujoco><worldbody><car name=\"car\"/></worldbody></mujoco>")
    }
}

fn platform() -> PlatformBuilder {
    Platform::builder()
        .world::<Garage>()
        .environment("mock")
        .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
}

#[test]
fn interfaces_step_every_tick_children_before_parents() {
    platform()
        .behaviour(|pl| async move {
            pl.wait_seconds(0.02).await?;
            Ok(())
        })
        .run()
        .unwrap();
    let steps = STEPS.with(|s| s.borrow().clone());
    assert_eq!(
        steps,
        [
            "/car/right",
            "/car/left",
            "/car",
            "/car/right",
            "/car/left",
            "/car"
        ]
    );
}

#[test]
fn behaviours_get_typed_handles_by_path_or_name() {
    platform()
        .behaviour(|pl| async move {
            let car: Car = pl.get("/car")?;
            let left: Motor = pl.get("/car/left")?;
            let right: Motor = pl.get("right")?;
            assert_eq!(left.joint, "car/left/axle");
            assert_eq!((left.speed, right.speed), (1.0, 2.0));
            pl.wait_seconds(0.03).await?;
            assert_eq!(car.left.ticks.get(), 3, "handles are shared, not copies");
            assert_eq!(car.right.speed, 2.0);
            let wrong = pl.get::<Car>("/car/left").err().unwrap();
            assert_eq!(
                wrong.to_string(),
                format!(
                    "/car/left is a {}, not a {}",
                    std::any::type_name::<Motor>(),
                    std::any::type_name::<Car>()
                )
            );
            let missing = pl.get::<Motor>("/car/lft").err().unwrap();
            assert_eq!(
                missing.to_string(),
                "no component at /car/lft; did you mean `/car/left`?"
            );
            let far = pl.get::<Motor>("/bgi").err().unwrap();
            assert_eq!(
                far.to_string(),
                "no component at /bgi; it has `/`, `/car`, `/car/left`, `/car/right`"
            );
            assert!(matches!(
                pl.get::<Garage>("/"),
                Err(yarok_core::component::HandleError::NoHandle { .. })
            ));
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn environments_that_components_do_not_support_fail_before_anything_binds() {
    let error = platform()
        .backend::<Real>(|_, _| Ok(MockBackend::new(0.01, true)))
        .environment("real")
        .build()
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        format!(
            "components cannot run in `real`: /car (Car) supports sim, mock; /car/left (Motor) \
             supports sim, mock; /car/right (Motor) supports sim, mock"
        )
    );
    let RuntimeError::Unsupported { components, .. } = error else {
        panic!("{error}");
    };
    assert_eq!(components[1].supports, ["sim", "mock"]);
    assert_eq!(STEPS.with(|s| s.borrow().len()), 0, "nothing was bound");
}

/// A plugin that runs only in `sim`, as a recorder of the simulation's state does.
struct SimOnly(Rc<Cell<bool>>);

impl Plugin for SimOnly {
    fn name(&self) -> String {
        "sim_only".to_owned()
    }

    fn environments(&self) -> Vec<&'static str> {
        vec![Sim::NAME]
    }

    fn start(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        self.0.set(true);
        Ok(())
    }

    fn step(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        Ok(())
    }
}

#[test]
fn plugins_in_environments_they_do_not_run_in_fail_before_anything_binds() {
    let started = Rc::new(Cell::new(false));
    let error = platform()
        .plugin(SimOnly(Rc::clone(&started)))
        .behaviour(|_| async { Ok(()) })
        .run()
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "plugin sim_only cannot run in `mock`: it runs in sim"
    );
    assert!(matches!(error, RuntimeError::PluginUnsupported { .. }));
    assert_eq!(STEPS.with(|s| s.borrow().len()), 0, "nothing was bound");
    assert!(!started.get());
    let ran = Rc::new(Cell::new(false));
    platform()
        .backend::<Sim>(|_, _| Ok(MockBackend::new(0.01, false)))
        .environment("sim")
        .plugin(SimOnly(Rc::clone(&started)))
        .behaviour({
            let ran = Rc::clone(&ran);
            move |_| async move {
                ran.set(true);
                Ok(())
            }
        })
        .run()
        .unwrap();
    assert!(started.get() && ran.get(), "in `sim` it runs");
}

struct Recorder {
    name: &'static str,
    log: Rc<RefCell<Vec<String>>>,
}

impl Plugin for Recorder {
    fn name(&self) -> String {
        self.name.to_owned()
    }

    fn start(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        self.log.borrow_mut().push(format!("{} start", self.name));
        Ok(())
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let pl = world.pl();
        self.log
            .borrow_mut()
            .push(format!("{} {}", self.name, pl.ticks()));
        if self.name == "failing" && pl.ticks() == 2 {
            return Err("disk full".into());
        }
        Ok(())
    }

    fn end(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        self.log.borrow_mut().push(format!("{} end", self.name));
        Ok(())
    }
}

#[test]
fn plugins_step_in_order_and_always_see_the_end() {
    let log = Rc::new(RefCell::new(Vec::new()));
    let recorder = |name| Recorder {
        name,
        log: Rc::clone(&log),
    };
    platform()
        .plugin(recorder("first"))
        .plugin(recorder("second"))
        .behaviour(|pl| async move {
            pl.wait_seconds(0.02).await?;
            Ok(())
        })
        .run()
        .unwrap();
    assert_eq!(
        *log.borrow(),
        [
            "first start",
            "second start",
            // A plugin steps after the clock has counted the tick.
            "first 1",
            "second 1",
            "first 2",
            "second 2",
            "first end",
            "second end"
        ]
    );

    log.borrow_mut().clear();
    let error = platform()
        .plugin(recorder("failing"))
        .plugin(recorder("after"))
        .behaviour(|pl| async move {
            pl.wait_forever().await?;
            Ok(())
        })
        .run()
        .unwrap_err();
    assert_eq!(error.to_string(), "plugin failing failed: disk full");
    assert_eq!(
        *log.borrow(),
        [
            "failing start",
            "after start",
            "failing 1",
            "after 1",
            "failing 2",
            "failing end",
            "after end"
        ]
    );
}

#[derive(serde::Deserialize)]
struct CounterSettings {
    every: i64,
}

#[test]
fn plugins_are_created_from_the_run_configuration() {
    let created = Rc::new(Cell::new(0i64));
    let seen = Rc::clone(&created);
    let config = RunConfig::from_toml("[plugins.counter]\nevery = 5\n", "run.toml").unwrap();
    platform()
        .config(config)
        .plugin_factory("counter", move |settings: CounterSettings| {
            seen.set(settings.every);
            Ok::<_, BoxError>(|_: &World<'_>| Ok(()))
        })
        .behaviour(|pl| async move {
            pl.tick().await?;
            Ok(())
        })
        .run()
        .unwrap();
    assert_eq!(created.get(), 5);
    let error = platform()
        .config(RunConfig::from_toml("[plugins.countr]\n", "run.toml").unwrap())
        .plugin_factory("counter", |_: CounterSettings| {
            Ok::<_, BoxError>(|_: &World<'_>| Ok(()))
        })
        .build()
        .unwrap_err();
    assert!(
        error
            .to_string()
            .contains("[plugins.countr] names no registered plugin; did you mean `counter`?"),
        "{error}"
    );
    let mut config = RunConfig::default();
    config.set("plugins/video/fps=30").unwrap();
    let error = platform()
        .config(config)
        .plugin_factory("counter", |_: CounterSettings| {
            Ok::<_, BoxError>(|_: &World<'_>| Ok(()))
        })
        .build()
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "--set plugins/video/fps=30: [plugins.video] names no registered plugin; it has `counter`"
    );
}

const RUN: &str = r#"
environment = "sim"

[components."/car/left"]
speed = 3.0

[components."/car/right"]
speed = 4.0

[behaviour]
laps = 2

[environments.mock.components."/car/left"]
speed = 5.0
"#;

fn speeds(builder: PlatformBuilder) -> (f64, f64, i64) {
    let result = Rc::new(RefCell::new((0.0, 0.0, 0)));
    let out = Rc::clone(&result);
    builder
        .backend::<Sim>(|_, _| Ok(MockBackend::new(0.01, false)))
        .behaviour_default("laps", 1)
        .behaviour(move |pl| async move {
            let (left, right): (Motor, Motor) = (pl.get("/car/left")?, pl.get("/car/right")?);
            let laps = pl.config().get("laps").and_then(|laps| laps.as_i64());
            *out.borrow_mut() = (left.speed, right.speed, laps.ok_or("laps")?);
            Ok(())
        })
        .run()
        .unwrap();
    result.take()
}

#[test]
fn configuration_layers_defaults_file_environment_and_command_line() {
    assert_eq!(
        speeds(platform()),
        (1.0, 2.0, 1),
        "defaults and tag attributes"
    );
    let file = || RunConfig::from_toml(RUN, "run.toml").unwrap();
    assert_eq!(
        speeds(platform().config(file())),
        (3.0, 4.0, 2),
        "the file's base layer"
    );
    assert_eq!(
        speeds(platform().config(file()).environment("mock")),
        (5.0, 4.0, 2),
        "the environment's layer"
    );
    let args = [
        "--env",
        "mock",
        "--set",
        "/car/right/speed=6",
        "--set",
        "behaviour/laps=7",
    ]
    .map(String::from);
    assert_eq!(
        speeds(platform().config(file()).args(args).unwrap()),
        (5.0, 6.0, 7),
        "the command line last"
    );
}

#[test]
fn unknown_names_in_the_configuration_are_errors_with_the_nearest_name() {
    let error = |toml: &str| {
        platform()
            .backend::<Sim>(|_, _| Ok(MockBackend::new(0.01, false)))
            .config(RunConfig::from_toml(toml, "run.toml").unwrap())
            .build()
            .unwrap_err()
            .to_string()
    };
    assert!(error("[components.\"/car/lft\"]\nspeed = 1.0").contains("did you mean `/car/left`?"));
    assert!(
        error("[components.\"/car/left\"]\nsped = 1.0")
            .contains("no config key `sped` (it has speed); did you mean `speed`?")
    );
    assert!(
        error("[components.\"/car/left\"]\nspeed = \"fast\"").contains("`speed` expects a number")
    );
    assert!(
        error("environment = \"mok\"")
            .contains("no backend for environment `mok` (available: mock, sim)")
    );
    assert!(
        error("[environments.mok.behaviour]\n")
            .contains("names no known environment; did you mean `mock`?")
    );
    assert!(error("[behaviour]\nlaps = 2").contains("[behaviour] no config key `laps`"));
    assert!(error("[platform]\nrealtim = true").contains("did you mean `realtime`?"));
    assert!(error("[interfaces.\"/car/lef\"]\nport = 1").contains("did you mean `/car/left`?"));
    let syntax = RunConfig::from_toml("[behaviour\nlaps = 2", "run.toml").unwrap_err();
    assert!(
        syntax.to_string().starts_with("run.toml: ") && syntax.to_string().contains("line 1"),
        "{syntax}"
    );
    let section = RunConfig::from_toml("[behavior]\nlaps = 2", "run.toml").unwrap_err();
    assert_eq!(
        section.to_string(),
        "run.toml: unknown section `behavior`; did you mean `behaviour`?"
    );
    let key = RunConfig::from_toml("enviroment = \"mock\"", "run.toml").unwrap_err();
    assert_eq!(
        key.to_string(),
        "run.toml: unknown section `enviroment`; did you mean `environment`?"
    );
}

/// A wrong value names where it was set: the file and key, or the `--set` argument.
#[test]
fn config_value_errors_name_where_the_value_was_set() {
    let error = |config: RunConfig| {
        platform()
            .backend::<Sim>(|_, _| Ok(MockBackend::new(0.01, false)))
            .config(config)
            .build()
            .unwrap_err()
            .to_string()
    };
    let file = |toml: &str| RunConfig::from_toml(toml, "run.toml").unwrap();
    assert_eq!(
        error(file("[platform]\nrealtime = \"yes\"")),
        "run.toml, key `platform.realtime`: [platform] `realtime` expects true or false, got \"yes\""
    );
    assert_eq!(
        error(file("[components.\"/car/left\"]\nspeed = \"fast\"")),
        "component /car/left, run.toml, key `components.\"/car/left\".speed` attribute `speed`: `speed` expects a number, got \"fast\""
    );
    let mut config = RunConfig::default();
    config.set("/car/lft/speed=2").unwrap();
    assert_eq!(
        error(config),
        "component /car/lft, --set /car/lft/speed=2 attribute `speed`: config names component /car/lft, which the world does not have; did you mean `/car/left`?"
    );
    let mut config = RunConfig::default();
    config.set("interfaces/bgi/gain=2").unwrap();
    assert_eq!(
        error(config),
        "--set interfaces/bgi/gain=2: [interfaces.\"/bgi\"] names no component; it has `/`, \
         `/car`, `/car/left`, `/car/right`"
    );
    let mut config = RunConfig::default();
    config.set("/bgi/speed=2").unwrap();
    assert!(error(config).ends_with(
        "config names component /bgi, which the world does not have; it has `/`, `/car`, \
             `/car/left`, `/car/right`"
    ),);
    let mut config = RunConfig::default();
    config.set("behaviour/laps=many").unwrap();
    assert!(
        error(config).starts_with("--set behaviour/laps=many: [behaviour] "),
        "behaviour values are checked too"
    );
}

/// `--config FILE` reads a run configuration file, which later `--set`s override; a value wrong
/// in the file names the file and key, a missing file names the file.
#[test]
fn config_files_are_read_from_the_command_line() {
    let dir = std::env::temp_dir().join(format!("yarok-config-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("run.toml");
    std::fs::write(&file, RUN).unwrap();
    let file_arg = file.to_str().unwrap().to_owned();
    let args = ["--config", &file_arg, "--env", "mock"].map(String::from);
    assert_eq!(speeds(platform().args(args).unwrap()), (5.0, 4.0, 2));
    let args = ["--config", &file_arg, "--set", "behaviour/laps=9"].map(String::from);
    assert_eq!(speeds(platform().args(args).unwrap()), (3.0, 4.0, 9));

    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[platform]\nrealtime = \"yes\"\n").unwrap();
    let error = platform()
        .backend::<Sim>(|_, _| Ok(MockBackend::new(0.01, false)))
        .args(["--config", bad.to_str().unwrap()].map(String::from))
        .unwrap()
        .build()
        .unwrap_err()
        .to_string();
    assert!(
        error.starts_with(&format!("{}, key `platform.realtime`: ", bad.display())),
        "{error}"
    );
    let missing = dir.join("missing.toml");
    let error = platform()
        .args(["--config", missing.to_str().unwrap()].map(String::from))
        .unwrap_err()
        .to_string();
    assert!(
        error.starts_with(&format!("{}: cannot read", missing.display())),
        "{error}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A component whose probe cannot make its image.
#[derive(Clone)]
struct BlindCamera;

impl Component for BlindCamera {
    fn declaration() -> Declaration {
        Declaration::new("blind_camera").template("<mujoco/>")
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Mock>();
    }
}

impl Interface<Mock> for BlindCamera {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        bind.probe("rgb", || Err("the lens cap is on".into()));
        Ok(BlindCamera)
    }
}

/// Reads every probe at start and keeps what each read said.
struct ProbeReader(Rc<RefCell<Vec<String>>>);

impl Plugin for ProbeReader {
    fn name(&self) -> String {
        "probe reader".to_owned()
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        for probe in world.probes() {
            let said = probe
                .read()
                .map_or_else(|e| e.to_string(), |_| "an image".into());
            self.0.borrow_mut().push(said);
        }
        Ok(())
    }

    fn step(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        Ok(())
    }
}

/// A world with a [`BlindCamera`] named `cam`.
struct Darkroom;

impl Component for Darkroom {
    fn declaration() -> Declaration {
        Declaration::new("darkroom")
            .uses::<BlindCamera>()
            .template(r#"<mujoco><worldbody><blind_camera name="cam"/></worldbody></mujoco>"#)
    }
}

#[test]
fn a_probe_that_cannot_read_says_which_probe_it_is() {
    let said = Rc::new(RefCell::new(Vec::new()));
    Platform::builder()
        .world::<Darkroom>()
        .environment("mock")
        .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
        .plugin(ProbeReader(Rc::clone(&said)))
        .behaviour(|pl| async move {
            pl.tick().await?;
            Ok(())
        })
        .run()
        .unwrap();
    assert_eq!(*said.borrow(), ["probe /cam/rgb: the lens cap is on"]);
}
