//! A component's typed config, declared once as a serde struct and read back whole: the
//! template sees every field, tag attributes and run configurations set them, and a wrong key
//! or value names where it was set and the nearest name, from `--set` and from a TOML file.

use std::cell::RefCell;
use std::rc::Rc;

use yarok::prelude::*;

/// How the fan blows.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
enum Mode {
    Steady,
    Gusty,
}

/// The fan's config, declared once.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
struct FanConfig {
    blades: u32,
    speed: f64,
    mode: Mode,
}

/// A fan whose handle is its config as bound.
#[derive(Clone)]
struct Fan(FanConfig);

impl Component for Fan {
    fn declaration() -> Declaration {
        Declaration::new("fan")
            .config(FanConfig {
                blades: 4,
                speed: 1.0,
                mode: Mode::Steady,
            })
            .template(
                r#"<mujoco><worldbody><body name="hub">
                     <for each="range(blades)" as="i">
                       <geom name="blade{i}" type="box" size="0.1 0.01 0.002" euler="0 0 {i * 360 / blades}"/>
                     </for>
                     <site name="{mode}_at_{speed}"/>
                   </body></worldbody></mujoco>"#,
            )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Mock>();
    }
}

impl Interface<Mock> for Fan {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        bind.config().map(Fan)
    }
}

/// A room with a three-bladed fan at `/fan`.
struct Room;
impl Component for Room {
    fn declaration() -> Declaration {
        Declaration::new("room")
            .uses::<Fan>()
            .template(r#"<mujoco><worldbody><fan name="fan" blades="3"/></worldbody></mujoco>"#)
    }
}

fn room() -> yarok::core::runtime::PlatformBuilder {
    yarok::platform().world::<Room>().environment("mock")
}

/// The fan's config as its interface read it, or the run's error.
fn bound(room: yarok::core::runtime::PlatformBuilder) -> Result<FanConfig, String> {
    let seen = Rc::new(RefCell::new(None));
    let out = Rc::clone(&seen);
    room.behaviour(move |pl| async move {
        let fan: Fan = pl.get("/fan")?;
        *out.borrow_mut() = Some(fan.0);
        Ok(())
    })
    .run()
    .map_err(|e| e.to_string())?;
    let seen = seen.borrow().clone();
    Ok(seen.expect("the behaviour ran"))
}

fn toml_file(dir: &tempfile::TempDir, text: &str) -> std::path::PathBuf {
    let path = dir.path().join("run.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn the_template_and_the_interface_see_the_same_typed_config() {
    let composed = yarok::core::compose::compose::<Room>().unwrap().to_xml();
    assert_eq!(
        composed.matches("name=\"fan/blade").count(),
        3,
        "{composed}"
    );
    assert!(composed.contains("name=\"fan/steady_at_1\""), "{composed}");

    assert_eq!(
        bound(room()).unwrap(),
        FanConfig {
            blades: 3,
            speed: 1.0,
            mode: Mode::Steady
        }
    );
    let dir = tempfile::tempdir().unwrap();
    let file = toml_file(&dir, "[components.\"/fan\"]\nmode = \"gusty\"\n");
    let set = room()
        .config_file(&file)
        .unwrap()
        .set("/fan/speed=2.5")
        .unwrap();
    assert_eq!(
        bound(set).unwrap(),
        FanConfig {
            blades: 3,
            speed: 2.5,
            mode: Mode::Gusty
        }
    );
}

#[test]
fn a_wrong_key_or_value_from_set_names_the_argument_and_the_nearest_key() {
    let error = |assignment: &str| bound(room().set(assignment).unwrap()).unwrap_err();
    assert_eq!(
        error("/fan/sped=2"),
        "component /fan, --set /fan/sped=2 attribute `sped`: no config key `sped` (it has \
         blades, speed, mode); did you mean `speed`?"
    );
    assert_eq!(
        error("/fan/blades=many"),
        "component /fan, --set /fan/blades=many attribute `blades`: `blades` expects an \
         integer, got \"many\""
    );
    assert_eq!(
        error("/fan/mode=gustyy"),
        "component /fan: --set /fan/mode=gustyy: `mode` unknown value `gustyy` (expected one \
         of steady, gusty); did you mean `gusty`?"
    );
}

#[test]
fn a_wrong_key_or_value_from_a_file_names_the_file_and_key_and_the_nearest_key() {
    let dir = tempfile::tempdir().unwrap();
    let error = |text: &str| {
        let file = toml_file(&dir, text);
        let message = bound(room().config_file(&file).unwrap()).unwrap_err();
        message.replace(&file.display().to_string(), "run.toml")
    };
    assert_eq!(
        error("[components.\"/fan\"]\nspeeed = 2\n"),
        "component /fan, run.toml, key `components.\"/fan\".speeed` attribute `speeed`: no \
         config key `speeed` (it has blades, speed, mode); did you mean `speed`?"
    );
    assert_eq!(
        error("[components.\"/fan\"]\nspeed = \"fast\"\n"),
        "component /fan, run.toml, key `components.\"/fan\".speed` attribute `speed`: `speed` expects a \
         number, got \"fast\""
    );
    assert_eq!(
        error("[components.\"/fan\"]\nmode = \"stedy\"\n"),
        "component /fan: run.toml, key `components.\"/fan\".mode`: `mode` unknown value `stedy` \
         (expected one of steady, gusty); did you mean `steady`?"
    );
}

/// A config with a field no template value can hold.
struct Nested;
impl Component for Nested {
    fn declaration() -> Declaration {
        #[derive(serde::Serialize)]
        struct Inner {
            x: f64,
        }
        #[derive(serde::Serialize)]
        struct Outer {
            inner: Inner,
        }
        Declaration::new("nested")
            .config(Outer {
                inner: Inner { x: 1.0 },
            })
            .template("<mujoco/>")
    }
}

#[test]
fn a_config_field_templates_cannot_hold_is_refused_at_compose() {
    let error = yarok::core::compose::compose::<Nested>()
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("declares a config yarok cannot hold: `inner` is a table, which config values cannot hold"),
        "{error}"
    );
}

/// A room with the fan placed by `pos=`, a key the fan's config does not have.
struct PlacedFanRoom;
impl Component for PlacedFanRoom {
    fn declaration() -> Declaration {
        Declaration::new("placed_fan_room")
            .uses::<Fan>()
            .template(r#"<mujoco><worldbody><fan name="fan" pos="0 0 1"/></worldbody></mujoco>"#)
    }
}

#[test]
fn placing_a_component_by_a_key_it_lacks_says_how_components_are_placed() {
    let error = yarok::core::compose::compose::<PlacedFanRoom>()
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("no config key `pos` (it has blades, speed, mode)")
            && error.contains("a component is placed by a `<body>` around its tag, by `parent=`"),
        "{error}"
    );
}
