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
use crate::grippers::Robotiq2f85;
use crate::probe_images;
use crate::robots::AnetA30;
use crate::robots::ur::{Arm, Ur5, Ur5e, pose_to_vector};

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

/// A component the bridge can command.
#[derive(Debug, Clone)]
enum Device {
    Arm(Arm),
    Gripper(Robotiq2f85),
    Printer(AnetA30),
}

/// A message for the bridge's thread to put.
struct Put {
    key: String,
    payload: Vec<u8>,
    png: bool,
}

/// A command received: the component path it is for, and its JSON.
struct Command {
    path: String,
    body: Result<Value, String>,
}

/// Publishes a world's state over [Zenoh](https://zenoh.io) and takes commands from it, in
/// `sim` and `real` alike. Keys, under `yarok/{world}` (`world` set, default `world`):
///
/// - `…/joint_states` and `…/tf` (`sim`): every joint coordinate's position and velocity, every
///   named body's pose — JSON shaped as the MCAP recorder's (`yarok.JointState`,
///   `foxglove.FrameTransforms`), `hz` times a second of platform time;
/// - `…{path}/state`: each arm (`{"time", "q", "qd", "tcp"}`, TCP as a UR pose vector),
///   gripper (`{"time", "position", "moving", "object_detected"}`) and printer (`{"time",
///   "at"}`), from their handles;
/// - `…{path}/{probe}`: each probe's image, PNG (`/arm/gripper/left_digit/image`), `image_hz`
///   times a second;
/// - commands to `…{path}/command`, JSON: an arm `{"move_j": [q…], "speed": …,
///   "acceleration": …}`, `{"move_l": [x, y, z, rx, ry, rz], …}`, `{"stop": true}`; a gripper
///   `{"move_to": 0–255, "speed": …, "force": …}`, `{"open": true}`, `{"close": true}`; a printer
///   `{"move_to": [x, y, z]}` (mm); the world (`yarok/{world}/command`) `{"stop": true}` ends the
///   run, `{"ping": n}` is answered at once. Each is answered on `…{path}/reply`:
///   `{"ok": true}` or `{"ok": false, "error": …}` (`{"pong": n}` for a ping).
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
    devices: Vec<(String, Device)>,
    sim: Option<SimState>,
    next_state: f64,
    next_image: f64,
}

impl ZenohBridge {
    /// A bridge with these settings; the session opens when the run starts.
    ///
    /// # Errors
    ///
    /// When a rate is not a positive number.
    pub fn new(settings: ZenohBridgeSettings) -> Result<Self, BoxError> {
        for (name, rate) in [("hz", settings.hz), ("image_hz", settings.image_hz)] {
            if !(rate > 0.0 && rate.is_finite()) {
                return Err(format!("`{name}` {rate} must be above 0").into());
            }
        }
        Ok(Self {
            settings,
            puts: None,
            commands: None,
            thread: None,
            devices: Vec::new(),
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
        for (path, device) in &self.devices {
            let state = match device {
                Device::Arm(arm) => json!({
                    "time": time, "q": arm.q(), "qd": arm.qd(),
                    "tcp": pose_to_vector(&arm.tcp_pose()),
                }),
                Device::Gripper(gripper) => json!({
                    "time": time, "position": gripper.position(), "moving": gripper.is_moving(),
                    "object_detected": gripper.object_detected(),
                }),
                Device::Printer(printer) => json!({ "time": time, "at": printer.at() }),
            };
            self.put_json(self.key(path, "state"), &state)?;
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
        for Command { path, body } in received {
            let reply = match body.and_then(|body| self.run(world, &path, &body)) {
                Ok(reply) => reply,
                Err(error) => json!({ "ok": false, "error": error }),
            };
            self.put_json(self.key(&path, "reply"), &reply)?;
        }
        Ok(())
    }

    fn run(&self, world: &World<'_>, path: &str, body: &Value) -> Result<Value, String> {
        let number = |key: &str| body.get(key).and_then(Value::as_f64);
        let six = |value: &Value| -> Result<[f64; 6], String> {
            serde_json::from_value(value.clone()).map_err(|_| "expected six numbers".to_owned())
        };
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
        let device = self
            .devices
            .iter()
            .find(|(p, _)| p.trim_matches('/') == path)
            .map(|(_, d)| d)
            .ok_or_else(|| format!("no component /{path} takes commands"))?;
        match device {
            Device::Arm(arm) => {
                let motion = if let Some(q) = body.get("move_j") {
                    arm.move_j(six(q)?)
                } else if let Some(pose) = body.get("move_l") {
                    arm.move_l_vector(six(pose)?)
                } else if body.get("stop").is_some() {
                    arm.stop();
                    return Ok(json!({ "ok": true }));
                } else {
                    return Err("an arm takes move_j, move_l or stop".into());
                };
                let motion = match number("speed") {
                    Some(speed) => motion.speed(speed),
                    None => motion,
                };
                let motion = match number("acceleration") {
                    Some(acceleration) => motion.acceleration(acceleration),
                    None => motion,
                };
                motion.start().map_err(|e| e.to_string())?;
            }
            Device::Gripper(gripper) => {
                let byte = |key: &str| number(key).map(|v| v.clamp(0.0, 255.0) as u8);
                let grip = if let Some(position) = byte("move_to") {
                    gripper.move_to(position)
                } else if body.get("open").is_some() {
                    gripper.open()
                } else if body.get("close").is_some() {
                    gripper.close()
                } else {
                    return Err("a gripper takes move_to, open or close".into());
                };
                let grip = match byte("speed") {
                    Some(speed) => grip.speed(speed),
                    None => grip,
                };
                match byte("force") {
                    Some(force) => grip.force(force),
                    None => grip,
                }
                .start();
            }
            Device::Printer(printer) => {
                let target: [f64; 3] = body
                    .get("move_to")
                    .and_then(|v| serde_json::from_value(v.clone()).ok())
                    .ok_or("a printer takes {\"move_to\": [x, y, z]} (mm)")?;
                printer.move_to(target);
            }
        }
        Ok(json!({ "ok": true }))
    }
}

/// The components of `world` that take commands.
fn devices(world: &World<'_>) -> Vec<(String, Device)> {
    let pl = world.pl();
    world
        .composition()
        .instances
        .iter()
        .filter_map(|instance| {
            let path = instance.path.clone();
            let device = if let Ok(arm) = pl.get::<Ur5e>(&path) {
                Device::Arm((*arm).clone())
            } else if let Ok(arm) = pl.get::<Ur5>(&path) {
                Device::Arm((*arm).clone())
            } else if let Ok(gripper) = pl.get::<Robotiq2f85>(&path) {
                Device::Gripper(gripper)
            } else if let Ok(printer) = pl.get::<AnetA30>(&path) {
                Device::Printer(printer)
            } else {
                return None;
            };
            Some((path, device))
        })
        .collect()
}

/// The Zenoh session on a thread of its own: puts what the plugin sends, hands commands back.
fn serve(
    config: zenoh::Config,
    commands_key: String,
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
    let subscriber = session
        .declare_subscriber(commands_key)
        .callback(move |sample| {
            let key = sample.key_expr().as_str();
            let path = key
                .strip_prefix(&prefix)
                .and_then(|rest| rest.strip_suffix("command"))
                .unwrap_or_default()
                .trim_matches('/')
                .to_owned();
            let body = serde_json::from_slice(&sample.payload().to_bytes())
                .map_err(|e| format!("not JSON: {e}"));
            let _ = commands.send(Command { path, body });
        })
        .wait();
    if let Err(error) = &subscriber {
        let _ = opened.send(Err(error.to_string()));
        return;
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
    drop(subscriber);
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
        let commands_key = format!("yarok/{}/**/command", self.settings.world);
        let thread = std::thread::Builder::new()
            .name("yarok-zenoh".into())
            .spawn(move || serve(config, commands_key, prefix, to_put, received, opened))?;
        match open.recv_timeout(Duration::from_secs(10)) {
            Ok(Ok(())) => {}
            Ok(Err(error)) => return Err(format!("Zenoh session: {error}").into()),
            Err(_) => return Err("the Zenoh session did not open within 10 s".into()),
        }
        self.puts = Some(puts);
        self.commands = Some(commands);
        self.thread = Some(thread);
        self.devices = devices(world);
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
