//! A user's own component (written here, not bundled) publishes a named state and accepts a
//! named command, and the plugins see it with no code naming its type: the MCAP recorder
//! records the state, read back by PyPI's `mcap` (a third-party reader, a separate process);
//! the Zenoh bridge (feature `zenoh`) publishes it and takes the command from the Zenoh
//! project's own Python client, answering bodies it refuses with an error naming the command
//! and the field, and changing nothing for them.

use std::cell::Cell;
use std::rc::Rc;

use yarok::prelude::*;
use yarok_test::peers;

/// A dimmer: its `level` state is its brightness and how many times it changed; its `set`
/// command changes the brightness.
#[derive(Clone)]
struct Dimmer {
    brightness: Rc<Cell<f64>>,
    changes: Rc<Cell<u32>>,
}

#[derive(serde::Serialize)]
struct Level {
    brightness: f64,
    changes: u32,
}

#[derive(serde::Deserialize)]
struct Set {
    brightness: f64,
}

impl Dimmer {
    fn set(&self, brightness: f64) -> Result<(), yarok::core::BoxError> {
        if !(0.0..=1.0).contains(&brightness) {
            return Err(format!("brightness {brightness} is not within 0–1").into());
        }
        self.brightness.set(brightness);
        self.changes.set(self.changes.get() + 1);
        Ok(())
    }
}

impl Component for Dimmer {
    fn declaration() -> Declaration {
        Declaration::new("dimmer").template("<mujoco/>")
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Mock>();
    }
}

impl Interface<Mock> for Dimmer {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        let dimmer = Dimmer {
            brightness: Rc::new(Cell::new(0.25)),
            changes: Rc::new(Cell::new(0)),
        };
        let shown = dimmer.clone();
        bind.state("level", move || Level {
            brightness: shown.brightness.get(),
            changes: shown.changes.get(),
        });
        let commanded = dimmer.clone();
        bind.command("set", move |Set { brightness }| commanded.set(brightness));
        Ok(dimmer)
    }
}

/// A room with a dimmer at `/dimmer`.
struct Room;
impl Component for Room {
    fn declaration() -> Declaration {
        Declaration::new("room")
            .uses::<Dimmer>()
            .template(r#"<mujoco><worldbody><dimmer name="dimmer"/></worldbody></mujoco>"#)
    }
}

#[test]
fn the_mcap_recorder_records_a_users_named_state() {
    let folder = tempfile::tempdir().unwrap();
    let mcap = folder.path().join("room.mcap");
    yarok::platform()
        .world::<Room>()
        .environment("mock")
        .set(&format!("plugins/mcap/path=\"{}\"", mcap.display()))
        .unwrap()
        .set("plugins/mcap/every=5")
        .unwrap()
        .behaviour(|pl| async move {
            let dimmer: Dimmer = pl.get("/dimmer")?;
            pl.wait_seconds(0.1).await?;
            dimmer.set(0.75)?;
            pl.wait_seconds(0.1).await?;
            Ok(())
        })
        .run()
        .unwrap();
    let summary = peers::run("mcap_summary.py", &[mcap.to_str().unwrap()]);
    assert!(
        summary.contains("topic /dimmer/level yarok.State json "),
        "{summary}"
    );
    let states: Vec<(f64, &str)> = summary
        .lines()
        .filter_map(|line| line.strip_prefix("state /dimmer/level "))
        .map(|line| {
            let (time, json) = line.split_once(' ').unwrap();
            (time.parse().unwrap(), json)
        })
        .collect();
    assert!(states.len() >= 8, "{summary}");
    let before = r#"{"brightness": 0.25, "changes": 0}"#;
    let after = r#"{"brightness": 0.75, "changes": 1}"#;
    for (time, json) in &states {
        // Plugins record a tick before behaviours see it: the change made at 0.1 s shows next.
        let expected = if *time < 0.1 + 1e-9 { before } else { after };
        assert_eq!(*json, expected, "at {time} s:\n{summary}");
    }
    assert!(states.iter().any(|(_, json)| *json == before), "{summary}");
    assert!(states.iter().any(|(_, json)| *json == after), "{summary}");
}

#[cfg(feature = "zenoh")]
#[test]
fn a_third_party_zenoh_client_reads_a_users_state_and_commands_it() {
    use std::time::{Duration, Instant};

    let port = 20000 + (std::process::id() + 7) % 20000;
    let endpoint = format!("tcp/127.0.0.1:{port}");
    let listen = format!("plugins/zenoh/listen=[{endpoint:?}]");
    let world = std::thread::spawn(move || {
        let changed_to = Rc::new(Cell::new(f64::NAN));
        let out = Rc::clone(&changed_to);
        yarok::platform()
            .world::<Room>()
            .environment("mock")
            .set(&listen)
            .unwrap()
            .set("plugins/zenoh/world=\"room\"")
            .unwrap()
            .set("platform/realtime=true")
            .unwrap()
            .behaviour(move |pl| async move {
                let dimmer: Dimmer = pl.get("/dimmer")?;
                let watched = dimmer.clone();
                let changed = pl
                    .wait(move || watched.changes.get() > 0)
                    .timeout(60.0)
                    .await;
                out.set(dimmer.brightness.get());
                changed?;
                // Long enough for the changed state to be published.
                pl.wait_seconds(1.0).await?;
                Ok(())
            })
            .run()
            .map_err(|e| e.to_string())?;
        Ok::<f64, String>(changed_to.get())
    });
    let started = Instant::now();
    while std::net::TcpStream::connect(("127.0.0.1", port as u16)).is_err() {
        assert!(
            started.elapsed() < Duration::from_secs(60) && !world.is_finished(),
            "no bridge"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    let printed = peers::run(
        "zenoh_named.py",
        &[
            &endpoint,
            "room",
            "dimmer",
            "level",
            "set",
            r#"{"brightness": 0.8}"#,
            "brightness",
            "0.8",
            r#"{"brightness": "bright"}"#,
            r#"{"brightness": 2}"#,
            "not json",
        ],
    );
    let refused: Vec<serde_json::Value> = printed
        .lines()
        .filter_map(|line| line.strip_prefix("refused "))
        .map(|reply| serde_json::from_str(reply).unwrap())
        .collect();
    let errors: Vec<&str> = refused
        .iter()
        .map(|reply| {
            assert_eq!(reply["ok"], false, "{printed}");
            reply["error"].as_str().unwrap()
        })
        .collect();
    assert_eq!(
        errors,
        [
            "command /dimmer/set: brightness: invalid type: string \"bright\", expected f64",
            "command /dimmer/set: brightness 2 is not within 0–1",
            "yarok/room/dimmer/set: the body is not JSON: expected ident at line 1 column 2",
        ],
        "{printed}"
    );
    let brightness = world.join().unwrap().unwrap();
    assert_eq!(brightness, 0.8);
    let state: serde_json::Value = serde_json::from_str(peers::field(&printed, "state")).unwrap();
    assert_eq!(state["brightness"], 0.25, "{printed}");
    assert_eq!(state["changes"], 0, "{printed}");
    assert!(state["time"].as_f64().is_some(), "{printed}");
    assert_eq!(peers::field(&printed, "reply"), r#"{"ok": true}"#);
    let changed: serde_json::Value =
        serde_json::from_str(peers::field(&printed, "changed")).unwrap();
    // The refused bodies changed nothing: the one change is the accepted command's.
    assert_eq!(changed["changes"], 1, "{printed}");
}
