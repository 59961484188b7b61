//! [`ZenohBridge`]: a world's state published over Zenoh, and commands taken from it.

use std::collections::HashMap;
use std::sync::mpsc::{self, Receiver, Sender};
use std::thread::JoinHandle;
use std::time::Duration;

use serde_json::{Value, json};
use yarok_core::BoxError;
use yarok_core::runtime::{Plugin, World};
use yarok_mjc::SimBackend;
use zenoh::Wait;

use super::recording_profile::{Foxglove, JointValues, RecordingProfile};
use super::sim_state::SimState;
use crate::probe_images;

/// How a [`ZenohBridge`] connects and what it publishes (`[plugins.zenoh]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ZenohBridgeSettings {
    /// The world's name in the key space: `yarok/{world}/…`.
    pub world: String,
    /// Zenoh endpoints to listen on (`tcp/127.0.0.1:7447`).
    pub listen: Vec<String>,
    /// Zenoh endpoints to connect to.
    pub connect: Vec<String>,
    /// Look for peers by multicast (off: only the endpoints given).
    pub scouting: bool,
    /// States published a second of platform time.
    pub hz: f64,
    /// Probe images published a second of platform time.
    pub image_hz: f64,
}

impl Default for ZenohBridgeSettings {
    fn default() -> Self {
        Self {
            world: "world".into(),
            listen: vec!["tcp/127.0.0.1:7447".into()],
            connect: Vec::new(),
            scouting: false,
            hz: 50.0,
            image_hz: 5.0,
        }
    }
}

/// A message for the bridge's thread to put.
struct Put {
    key: String,
    payload: Vec<u8>,
    png: bool,
}

/// A command received: the component path it is for (no leading `/`; empty for the world's),
/// its name, and its JSON.
struct Command {
    path: String,
    name: String,
    body: Result<Value, String>,
}

impl Command {
    /// The command that came on `key` (under the world's `prefix`) with the body `payload`, or
    /// the size of one larger than [`MAX_COMMAND_BYTES`] (refused unread). A body that is not
    /// JSON, or is too large, is an error the reply will carry.
    fn received(key: &str, prefix: &str, payload: Result<&[u8], usize>) -> Self {
        let (path, name) = key
            .strip_prefix(prefix)
            .unwrap_or_default()
            .rsplit_once('/')
            .unwrap_or(("", "command"));
        let body = match payload {
            Ok(payload) => serde_json::from_slice(payload)
                .map_err(|e| format!("{key}: the body is not JSON: {e}")),
            Err(size) => Err(format!(
                "{key}: the command is {size} bytes, more than the {MAX_COMMAND_BYTES} a command \
                 may be"
            )),
        };
        Self {
            path: path.to_owned(),
            name: name.to_owned(),
            body,
        }
    }
}

/// Publishes a world's state over [Zenoh](https://zenoh.io) and takes commands from it, in
/// `sim` and `real` alike. Keys, under `yarok/{world}` (`world` set, default `world`):
///
/// - `…/joint_states` and `…/tf` (`sim`): every joint coordinate's position and velocity, every
///   named body's pose — JSON shaped as the MCAP recorder's (`yarok.JointState`,
///   `foxglove.FrameTransforms`), `hz` times a second of platform time;
/// - `…{path}/{name}`: every component's [named states](yarok_core::component::NamedState),
///   JSON, with the platform `time` added to an object, `hz` times a second — an arm's `state`
///   (`{"time", "q", "qd", "tcp"}`), a gripper's (`{"time", "position", "moving",
///   "object_detected"}`), a printer's (`{"time", "at"}`), and any component's of your own;
/// - `…{path}/{probe}`: each probe's image, PNG (`/arm/gripper/left_digit/image`), `image_hz`
///   times a second;
/// - commands to `…{path}/{name}`, JSON: every component's
///   [named commands](yarok_core::component::NamedCommand) — an arm's `command`
///   (`{"move_j": [q…], "speed": …, "acceleration": …}`, `{"move_l": [x, y, z, rx, ry, rz],
///   …}`, `{"stop": true}`), a gripper's (`{"move_to": 0–255, "speed": …, "force": …}`,
///   `{"open": true}`, `{"close": true}`), a printer's (`{"move_to": [x, y, z]}`, mm); the world
///   (`yarok/{world}/command`) `{"stop": true}` ends the run, `{"ping": n}` is answered at once.
///   Each is answered on `…{path}/reply`: `{"ok": true}` or `{"ok": false, "error": …}`
///   (`{"pong": n}` for a ping); one larger than 64 KiB is refused unread, and logged.
///
/// A world holds its keys while it runs (a Zenoh liveliness token on `yarok/{world}`): a second
/// world bridging the same keys on the same network is refused when it starts.
///
/// Zenoh runs on a thread of its own (its API needs a multi-threaded tokio runtime; the
/// platform's is single-threaded). Registered by `yarok::platform()` (feature `zenoh`) as
/// `zenoh`; `yarok run WORLD --bridge` adds it.
#[derive(Debug)]
pub struct ZenohBridge {
    settings: ZenohBridgeSettings,
    puts: Option<Sender<Put>>,
    commands: Option<Receiver<Command>>,
    thread: Option<JoinHandle<()>>,
    sim: Option<SimState>,
    next_state: f64,
    next_image: f64,
}

impl ZenohBridge {
    /// A bridge with these settings; the session opens when the run starts.
    ///
    /// # Errors
    ///
    /// When a rate is not a positive number, or `world` is not a plain key: empty, or with
    /// an empty chunk or one of Zenoh's wildcard and reserved characters (`*`, `$`, `?`, `#`),
    /// which would make it match other worlds' keys.
    pub fn new(settings: ZenohBridgeSettings) -> Result<Self, BoxError> {
        for (name, rate) in [("hz", settings.hz), ("image_hz", settings.image_hz)] {
            if !(rate > 0.0 && rate.is_finite()) {
                return Err(format!("`{name}` {rate} must be above 0").into());
            }
        }
        let world = &settings.world;
        if world.split('/').any(str::is_empty) || world.contains(['*', '$', '?', '#']) {
            return Err(format!(
                "`world` {world:?} is no plain key: give chunks of letters, digits, `_` or `-` \
                 joined by `/`, with no `*`, `$`, `?` or `#`"
            )
            .into());
        }
        Ok(Self {
            settings,
            puts: None,
            commands: None,
            thread: None,
            sim: None,
            next_state: 0.0,
            next_image: 0.0,
        })
    }

    fn key(&self, path: &str, leaf: &str) -> String {
        let path = path.trim_matches('/');
        if path.is_empty() {
            format!("yarok/{}/{leaf}", self.settings.world)
        } else {
            format!("yarok/{}/{path}/{leaf}", self.settings.world)
        }
    }

    fn put(&self, key: String, payload: Vec<u8>, png: bool) -> Result<(), BoxError> {
        let puts = self.puts.as_ref().ok_or("the bridge has not started")?;
        puts.send(Put { key, payload, png })
            .map_err(|_| "the Zenoh session has ended".into())
    }

    fn put_json(&self, key: String, value: &Value) -> Result<(), BoxError> {
        self.put(key, serde_json::to_vec(value)?, false)
    }

    fn publish_states(&self, world: &World<'_>, time: f64) -> Result<(), BoxError> {
        if let (Some(state), Some(sim)) = (&self.sim, world.backend::<SimBackend>()) {
            let (positions, velocities) = state.joint_values(sim);
            let joints = JointValues {
                names: state.joint_names(),
                positions: &positions,
                velocities: &velocities,
            };
            self.put(
                self.key("", "joint_states"),
                Foxglove.joint_state(time, &joints),
                false,
            )?;
            let poses = Foxglove.transforms(time, state.frame_names(), &state.poses(sim));
            self.put(self.key("", "tf"), poses, false)?;
        }
        for state in world.states() {
            let mut value = state.read()?;
            if let Value::Object(fields) = &mut value {
                fields.insert("time".into(), json!(time));
            }
            self.put_json(self.key(state.component(), state.name()), &value)?;
        }
        Ok(())
    }

    fn publish_images(&self, world: &World<'_>) -> Result<(), BoxError> {
        for probe in world.probes() {
            let image = probe.read()?;
            self.put(
                self.key(probe.component(), probe.name()),
                probe_images::png(&image)?,
                true,
            )?;
        }
        Ok(())
    }

    /// Runs the commands received; each is answered.
    fn run_commands(&self, world: &World<'_>) -> Result<(), BoxError> {
        let Some(commands) = &self.commands else {
            return Ok(());
        };
        let received: Vec<Command> = commands.try_iter().collect();
        for Command { path, name, body } in received {
            let reply = match body.and_then(|body| self.run(world, &path, &name, body)) {
                Ok(reply) => reply,
                Err(error) => json!({ "ok": false, "error": error }),
            };
            self.put_json(self.key(&path, "reply"), &reply)?;
        }
        Ok(())
    }

    fn run(&self, world: &World<'_>, path: &str, name: &str, body: Value) -> Result<Value, String> {
        if path.is_empty() {
            if let Some(n) = body.get("ping") {
                return Ok(json!({ "pong": n }));
            }
            if body.get("stop").and_then(Value::as_bool) == Some(true) {
                world.pl().stop();
                return Ok(json!({ "ok": true }));
            }
            return Err("the world takes {\"stop\": true} or {\"ping\": n}".into());
        }
        let command = world
            .command(&format!("/{path}"), name)
            .ok_or_else(|| format!("no component /{path} takes `{name}` commands"))?;
        command.run(body).map_err(|e| e.to_string())?;
        Ok(json!({ "ok": true }))
    }
}

/// The keys commands come on: `command` under any path (the world's and its components'),
/// and every other name a component takes commands by.
fn command_keys(world: &World<'_>, prefix: &str) -> Vec<String> {
    // `**` matches no chunk too: the world's own `…/command` is among these.
    let mut keys = vec![format!("{prefix}**/command")];
    for command in world.commands() {
        let key = format!("{prefix}**/{}", command.name());
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys
}

/// How long a starting bridge asks whether another world already holds its keys.
const LIVELINESS_QUERY: Duration = Duration::from_millis(500);

/// The key of a live world bridging `world`, if the network has one.
fn live_world(session: &zenoh::Session, world: &str) -> Option<String> {
    let replies = session
        .liveliness()
        .get(world)
        .timeout(LIVELINESS_QUERY)
        .wait()
        .ok()?;
    while let Ok(reply) = replies.recv() {
        if let Ok(sample) = reply.result() {
            return Some(sample.key_expr().as_str().to_owned());
        }
    }
    None
}

/// The most bytes a command may hold: a command names a motion or a grip, never data; a larger
/// one is refused (answered, and logged) unread.
const MAX_COMMAND_BYTES: usize = 64 * 1024;

/// The Zenoh session on a thread of its own: puts what the plugin sends, hands commands back.
fn serve(
    config: zenoh::Config,
    command_keys: Vec<String>,
    prefix: String,
    puts: Receiver<Put>,
    commands: Sender<Command>,
    opened: Sender<Result<(), String>>,
) {
    let session = match zenoh::open(config).wait() {
        Ok(session) => session,
        Err(error) => {
            let _ = opened.send(Err(error.to_string()));
            return;
        }
    };
    // A world holds its keys while it runs: a second on the same keys would obey the first's
    // commands and mix its states in.
    let world = prefix.trim_end_matches('/').to_owned();
    if let Some(other) = live_world(&session, &world) {
        let _ = opened.send(Err(format!(
            "another world already bridges {world} (seen as {other}): two would both obey its \
             commands and mix their states; give this one another `world`"
        )));
        return;
    }
    let _alive = match session.liveliness().declare_token(world.as_str()).wait() {
        Ok(token) => token,
        Err(error) => {
            let _ = opened.send(Err(error.to_string()));
            return;
        }
    };
    let mut subscribers = Vec::new();
    for key in command_keys {
        let (prefix, commands) = (prefix.clone(), commands.clone());
        let subscriber = session
            .declare_subscriber(key)
            .callback(move |sample| {
                let key = sample.key_expr().as_str();
                let payload = sample.payload();
                let command = if payload.len() > MAX_COMMAND_BYTES {
                    Command::received(key, &prefix, Err(payload.len()))
                } else {
                    Command::received(key, &prefix, Ok(&payload.to_bytes()))
                };
                if let Err(error) = &command.body {
                    tracing::warn!("{error}");
                }
                let _ = commands.send(command);
            })
            .wait();
        match subscriber {
            Ok(subscriber) => subscribers.push(subscriber),
            Err(error) => {
                let _ = opened.send(Err(error.to_string()));
                return;
            }
        }
    }
    let _ = opened.send(Ok(()));
    let mut publishers = HashMap::new();
    while let Ok(Put { key, payload, png }) = puts.recv() {
        if !publishers.contains_key(&key) {
            let encoding = if png {
                zenoh::bytes::Encoding::IMAGE_PNG
            } else {
                zenoh::bytes::Encoding::APPLICATION_JSON
            };
            match session
                .declare_publisher(key.clone())
                .encoding(encoding)
                .wait()
            {
                Ok(publisher) => drop(publishers.insert(key.clone(), publisher)),
                Err(error) => tracing::warn!(%key, %error, "cannot publish"),
            }
        }
        if let Some(publisher) = publishers.get(&key)
            && let Err(error) = publisher.put(payload).wait()
        {
            tracing::warn!(%key, %error, "cannot publish");
        }
    }
    drop(subscribers);
    drop(publishers);
    let _ = session.close().wait();
}

impl Plugin for ZenohBridge {
    fn name(&self) -> String {
        format!("zenoh (yarok/{})", self.settings.world)
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let mut config = zenoh::Config::default();
        let setting = |config: &mut zenoh::Config, key: &str, value: String| {
            config
                .insert_json5(key, &value)
                .map_err(|e| format!("zenoh setting {key} = {value}: {e}"))
        };
        setting(&mut config, "mode", "\"peer\"".into())?;
        setting(
            &mut config,
            "listen/endpoints",
            serde_json::to_string(&self.settings.listen)?,
        )?;
        setting(
            &mut config,
            "connect/endpoints",
            serde_json::to_string(&self.settings.connect)?,
        )?;
        setting(
            &mut config,
            "scouting/multicast/enabled",
            self.settings.scouting.to_string(),
        )?;
        let (puts, to_put) = mpsc::channel();
        let (received, commands) = mpsc::channel();
        let (opened, open) = mpsc::channel();
        let prefix = format!("yarok/{}/", self.settings.world);
        let command_keys = command_keys(world, &prefix);
        let thread = std::thread::Builder::new()
            .name("yarok-zenoh".into())
            .spawn(move || serve(config, command_keys, prefix, to_put, received, opened))?;
        match open.recv_timeout(Duration::from_secs(10)) {
            Ok(Ok(())) => {}
            Ok(Err(error)) => return Err(format!("Zenoh session: {error}").into()),
            Err(_) => return Err("the Zenoh session did not open within 10 s".into()),
        }
        self.puts = Some(puts);
        self.commands = Some(commands);
        self.thread = Some(thread);
        self.sim = world.backend::<SimBackend>().map(SimState::of);
        Ok(())
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let time = world
            .backend::<SimBackend>()
            .map_or(world.pl().time(), |sim| sim.data().time());
        self.run_commands(world)?;
        if time + 1e-9 >= self.next_state {
            self.next_state += 1.0 / self.settings.hz;
            self.publish_states(world, time)?;
        }
        if time + 1e-9 >= self.next_image {
            self.next_image += 1.0 / self.settings.image_hz;
            self.publish_images(world)?;
        }
        Ok(())
    }

    fn end(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.run_commands(world)?;
        self.puts = None;
        if let Some(thread) = self.thread.take() {
            thread.join().map_err(|_| "the Zenoh thread panicked")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use yarok_test::generator::Generator;

    use super::{Command, MAX_COMMAND_BYTES};

    /// 100 000 generated keys and payloads (JSON, JSON cut or flipped, bytes, sizes past the
    /// limit) each become a command to answer: the path and name under the world's keys, and
    /// the body or the reason it is refused. None panics.
    #[test]
    fn every_received_key_and_payload_becomes_a_command_to_answer() {
        let prefix = "yarok/world/";
        let keys = [
            "yarok/world/command",
            "yarok/world/arm/command",
            "yarok/world/gripper/command",
            "yarok/world/a/b/c/grip",
            "yarok/world/",
            "yarok/other/arm/command",
        ];
        let bodies: [&[u8]; 6] = [
            br#"{"move_j": [0.1, -1.5, 1.5, -1.5, -1.57, 0.0], "speed": 0.5}"#,
            br#"{"move_to": 255}"#,
            br#"{"ping": 1e308}"#,
            br#"[1, 2, {"a": null}]"#,
            b"\"\\u0000\"",
            b"",
        ];
        let mut generator = Generator(0x00b2_1d6e);
        let (mut taken, mut refused) = (0, 0);
        for _ in 0..100_000 {
            let key = generator.pick(&keys);
            let mut body = bodies[generator.below(bodies.len())].to_vec();
            match generator.below(4) {
                0 => body.truncate(generator.below(body.len() + 1)),
                1 if !body.is_empty() => {
                    let at = generator.below(body.len());
                    body[at] = generator.next_u64() as u8;
                }
                2 => {
                    let length = generator.below(64);
                    body = generator.bytes(length);
                }
                _ => {}
            }
            let payload = match generator.below(50) {
                0 => Err(MAX_COMMAND_BYTES + 1 + generator.below(1 << 30)),
                _ => Ok(body.as_slice()),
            };
            let command = Command::received(key, prefix, payload);
            match &command.body {
                Ok(_) => taken += 1,
                Err(error) => {
                    assert!(error.starts_with(key), "{error}");
                    refused += 1;
                }
            }
            // Under the world's keys, the path and the name are the key's; the world's own
            // command has no path.
            if let Some(under) = key.strip_prefix(prefix).filter(|under| !under.is_empty()) {
                let rebuilt = match command.path.as_str() {
                    "" => command.name.clone(),
                    path => format!("{path}/{}", command.name),
                };
                assert_eq!(rebuilt, under);
            }
        }
        assert!(
            taken > 10_000 && refused > 10_000,
            "{taken} taken, {refused} refused"
        );
    }
}
