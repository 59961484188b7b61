//! A fake UR controller for tests, on a loopback address of its own, in a CB3 (3.15) or an
//! e-Series (5.11) profile: its RTDE server (port 30004) answers recipes from the controller's
//! variable table and streams data packages at the recipe's rate; its dashboard server (port
//! 29999) powers the arm, releases its brakes, unlocks protective stops (not within 5 s of
//! one) and loads and plays programs, with UR's replies; its Robotiq gripper socket (port
//! 63352) activates a 2F-85 whose fingers move in time at the speed asked for and stop on an
//! object the test places, or fault when told to. The arm holds the joint positions the test
//! sets. Shared by yarok-hw's tests and the workspace's.
#![allow(dead_code)]

use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::io::{AsyncBufReadExt, AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use yarok_hw::ur::rtde::{
    ControllerVersion, Reply, Request, RtdeType, Value, input_type, output_type, take_frame,
};

/// RTDE's and the dashboard's ports, which third-party clients do not let one change.
pub(crate) const RTDE_PORT: u16 = 30004;
pub(crate) const DASHBOARD_PORT: u16 = 29999;
/// The Robotiq URCap's gripper socket.
pub(crate) const GRIPPER_PORT: u16 = 63352;

/// Which controller it plays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Profile {
    /// A CB3 controller, software 3.15: RTDE up to 125 Hz.
    Cb3,
    /// An e-Series controller, software 5.11: RTDE up to 500 Hz.
    ESeries,
}

impl Profile {
    pub(crate) fn version(self) -> ControllerVersion {
        match self {
            Profile::Cb3 => ControllerVersion {
                major: 3,
                minor: 15,
                bugfix: 7,
                build: 106_331,
            },
            Profile::ESeries => ControllerVersion {
                major: 5,
                minor: 11,
                bugfix: 1,
                build: 108_318,
            },
        }
    }

    /// The dashboard's `PolyscopeVersion` reply.
    fn polyscope(self) -> String {
        let ControllerVersion {
            major,
            minor,
            bugfix,
            build,
        } = self.version();
        format!("URSoftware {major}.{minor}.{bugfix}.{build} (Mar 22 2022)")
    }

    fn max_frequency(self) -> f64 {
        match self {
            Profile::Cb3 => 125.0,
            Profile::ESeries => 500.0,
        }
    }
}

/// What the controller's clients see and set.
struct Shared {
    profile: Profile,
    started: Instant,
    joints: Mutex<[f64; 6]>,
    /// Input variables clients have written.
    inputs: Mutex<HashMap<String, Value>>,
    /// Output variables clients asked for, in order.
    asked: Mutex<Vec<String>>,
    arm: Mutex<Arm>,
    fingers: Mutex<Fingers>,
}

/// The gripper's registers and its fingers' motion.
#[derive(Debug, Clone)]
pub(crate) struct Fingers {
    act: u8,
    gto: u8,
    pub(crate) sta: u8,
    pub(crate) flt: u8,
    pub(crate) obj: u8,
    pub(crate) pre: u8,
    target: u8,
    speed: u8,
    pub(crate) force: u8,
    /// Finger position, 0 … 255, as a real number while moving.
    position: f64,
    activating_since: Option<Instant>,
    updated: Instant,
    /// Where closing fingers meet an object, if one is between them.
    pub(crate) object_at: Option<u8>,
    /// Every SET command, in order.
    pub(crate) commands: Vec<String>,
}

impl Fingers {
    pub(crate) fn position(&self) -> u8 {
        self.position.round() as u8
    }

    /// Advances activation and motion to `now`.
    fn update(&mut self, now: Instant) {
        let elapsed = now.duration_since(self.updated).as_secs_f64();
        self.updated = now;
        if self.sta == 1
            && self
                .activating_since
                .is_some_and(|since| now.duration_since(since) >= Duration::from_millis(200))
        {
            self.sta = 3;
        }
        if self.sta != 3 || self.gto != 1 || self.obj != 0 || self.flt != 0 {
            return;
        }
        // A full stroke takes 1.5 s at speed 0 and 0.4 s at speed 255.
        let rate = 255.0 / (1.5 - 1.1 * f64::from(self.speed) / 255.0);
        let target = f64::from(self.target);
        let step = rate * elapsed;
        let closing = target > self.position;
        let mut next = if closing {
            (self.position + step).min(target)
        } else {
            (self.position - step).max(target)
        };
        if let Some(object) = self.object_at.map(f64::from)
            && closing
            && self.position <= object
            && next >= object
        {
            self.position = object;
            self.obj = 2;
            return;
        }
        if (next - target).abs() < 1e-9 {
            next = target;
            self.obj = 3;
        }
        self.position = next;
    }
}

/// The arm's power, safety and program, as the dashboard reports and changes them.
#[derive(Debug, Clone)]
pub(crate) struct Arm {
    pub(crate) robot_mode: &'static str,
    pub(crate) safety: &'static str,
    /// When the protective stop happened.
    pub(crate) stopped_at: Option<Instant>,
    pub(crate) program: Option<String>,
    pub(crate) playing: bool,
}

/// A fake controller serving RTDE on `host`, on a thread of its own until dropped.
pub(crate) struct FakeController {
    /// Its loopback address, unique to it.
    pub(crate) host: String,
    shared: Arc<Shared>,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

/// A loopback address no other fake of this process or another test process uses.
fn unique_loopback() -> String {
    static NEXT: AtomicU32 = AtomicU32::new(1);
    let pid = std::process::id();
    let own = NEXT.fetch_add(1, Ordering::Relaxed) % 254 + 1;
    format!("127.{}.{}.{own}", (pid >> 8) & 0xFF, pid & 0xFF)
}

impl FakeController {
    pub(crate) fn start(profile: Profile) -> Self {
        let host = unique_loopback();
        let shared = Arc::new(Shared {
            profile,
            started: Instant::now(),
            joints: Mutex::new([0.0, -FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2, 0.0]),
            inputs: Mutex::new(HashMap::new()),
            asked: Mutex::new(Vec::new()),
            arm: Mutex::new(Arm {
                robot_mode: "POWER_OFF",
                safety: "NORMAL",
                stopped_at: None,
                program: None,
                playing: false,
            }),
            fingers: Mutex::new(Fingers {
                act: 0,
                gto: 0,
                sta: 0,
                flt: 0,
                obj: 0,
                pre: 0,
                target: 0,
                speed: 0,
                force: 0,
                position: 0.0,
                activating_since: None,
                updated: Instant::now(),
                object_at: None,
                commands: Vec::new(),
            }),
        });
        let address = |port: u16| -> SocketAddr { format!("{host}:{port}").parse().unwrap() };
        let (rtde, dashboard, gripper) = (
            address(RTDE_PORT),
            address(DASHBOARD_PORT),
            address(GRIPPER_PORT),
        );
        let (bound_tx, bound_rx) = std::sync::mpsc::channel();
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let serving = Arc::clone(&shared);
        let thread = std::thread::spawn(move || {
            let runtime = tokio::runtime::Builder::new_current_thread()
                .enable_all()
                .build()
                .unwrap();
            runtime.block_on(async move {
                let rtde = TcpListener::bind(rtde).await.expect("the RTDE port binds");
                let dashboard = TcpListener::bind(dashboard)
                    .await
                    .expect("the dashboard port binds");
                let gripper = TcpListener::bind(gripper)
                    .await
                    .expect("the gripper port binds");
                bound_tx.send(()).unwrap();
                let accepting = async {
                    loop {
                        tokio::select! {
                            Ok((stream, _)) = rtde.accept() => {
                                tokio::spawn(serve_rtde(stream, Arc::clone(&serving)));
                            }
                            Ok((stream, _)) = dashboard.accept() => {
                                tokio::spawn(serve_dashboard(stream, Arc::clone(&serving)));
                            }
                            Ok((stream, _)) = gripper.accept() => {
                                tokio::spawn(serve_gripper(stream, Arc::clone(&serving)));
                            }
                        }
                    }
                };
                tokio::select! {
                    () = accepting => {}
                    _ = stopped => {}
                }
            });
        });
        bound_rx.recv().expect("the fake controller starts");
        Self {
            host,
            shared,
            stop: Some(stop),
            thread: Some(thread),
        }
    }

    /// Puts the arm at `q` (radians).
    pub(crate) fn set_joints(&self, q: [f64; 6]) {
        *self.shared.joints.lock().unwrap() = q;
    }

    pub(crate) fn joints(&self) -> [f64; 6] {
        *self.shared.joints.lock().unwrap()
    }

    /// The value a client last wrote to the input variable `name`.
    pub(crate) fn input(&self, name: &str) -> Option<Value> {
        self.shared.inputs.lock().unwrap().get(name).copied()
    }

    /// The arm's power, safety and program now.
    pub(crate) fn arm(&self) -> Arm {
        self.shared.arm.lock().unwrap().clone()
    }

    /// A protective stop, `ago` in the past.
    pub(crate) fn protective_stop(&self, ago: Duration) {
        let mut arm = self.shared.arm.lock().unwrap();
        arm.safety = "PROTECTIVE_STOP";
        arm.stopped_at = Some(Instant::now() - ago);
        arm.playing = false;
    }

    /// The gripper now.
    pub(crate) fn fingers(&self) -> Fingers {
        let mut fingers = self.shared.fingers.lock().unwrap();
        fingers.update(Instant::now());
        fingers.clone()
    }

    /// Puts an object between the fingers: closing, they stop at `position`.
    pub(crate) fn place_object(&self, position: Option<u8>) {
        self.shared.fingers.lock().unwrap().object_at = position;
    }

    /// Makes the gripper report fault `code` (its fingers stop).
    pub(crate) fn gripper_fault(&self, code: u8) {
        self.shared.fingers.lock().unwrap().flt = code;
    }

    /// The output variables clients asked for so far.
    pub(crate) fn asked(&self) -> Vec<String> {
        self.shared.asked.lock().unwrap().clone()
    }
}

impl Drop for FakeController {
    fn drop(&mut self) {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

impl Shared {
    /// The output variable `name`'s value now.
    fn output(&self, name: &str, rtde_type: RtdeType) -> Value {
        match name {
            "timestamp" => Value::Double(self.started.elapsed().as_secs_f64()),
            "actual_q" | "target_q" => Value::Vector6d(*self.joints.lock().unwrap()),
            "robot_mode" => Value::Int32(7),
            "safety_mode" | "safety_status" => Value::Int32(1),
            "joint_mode" => Value::Vector6Int32([253; 6]),
            "runtime_state" => Value::Uint32(1),
            "robot_status_bits" => Value::Uint32(1),
            "speed_scaling" | "target_speed_fraction" => Value::Double(1.0),
            _ => self
                .inputs
                .lock()
                .unwrap()
                .get(name)
                .copied()
                .unwrap_or_else(|| zero(rtde_type)),
        }
    }
}

fn zero(rtde_type: RtdeType) -> Value {
    match rtde_type {
        RtdeType::Bool => Value::Bool(false),
        RtdeType::Uint8 => Value::Uint8(0),
        RtdeType::Uint32 => Value::Uint32(0),
        RtdeType::Uint64 => Value::Uint64(0),
        RtdeType::Int32 => Value::Int32(0),
        RtdeType::Double => Value::Double(0.0),
        RtdeType::Vector3d => Value::Vector3d([0.0; 3]),
        RtdeType::Vector6d => Value::Vector6d([0.0; 6]),
        RtdeType::Vector6Int32 => Value::Vector6Int32([0; 6]),
        _ => Value::Vector6Uint32([0; 6]),
    }
}

/// Names as a client sent them, without the empty entry a trailing comma leaves (ur_rtde ends
/// every list with one; a real controller ignores it).
fn named(names: Vec<String>) -> Vec<String> {
    names.into_iter().filter(|name| !name.is_empty()).collect()
}

/// An output recipe being streamed: its id, variables and period.
type Outputs = (u8, Vec<(String, RtdeType)>, Duration);

/// One client's RTDE session.
async fn serve_rtde(stream: TcpStream, shared: Arc<Shared>) {
    let (mut reader, mut writer) = stream.into_split();
    let mut buffer = Vec::new();
    let mut outputs: Option<Outputs> = None;
    let mut inputs: HashMap<u8, Vec<(String, RtdeType)>> = HashMap::new();
    let (mut next_output, mut next_input) = (1u8, 1u8);
    let mut streaming: Option<tokio::time::Interval> = None;
    loop {
        let tick = async {
            match &mut streaming {
                Some(interval) => interval.tick().await,
                None => std::future::pending().await,
            }
        };
        let mut replies = Vec::new();
        tokio::select! {
            read = reader.read_buf(&mut buffer) => {
                if !matches!(read, Ok(1..)) {
                    return;
                }
                while let Ok(Some((kind, body))) = take_frame(&mut buffer) {
                    let Ok(request) = Request::decode(kind, &body) else { return };
                    match request {
                        Request::ProtocolVersion(version) => {
                            replies.push(Reply::ProtocolVersion { accepted: version == 2 });
                        }
                        Request::ControllerVersion => {
                            replies.push(Reply::ControllerVersion(shared.profile.version()));
                        }
                        Request::SetupOutputs { frequency, names } => {
                            let names = named(names);
                            shared.asked.lock().unwrap().extend(names.iter().cloned());
                            let types: Vec<Option<RtdeType>> =
                                names.iter().map(|name| output_type(name)).collect();
                            let rate_ok = frequency > 0.0 && frequency <= shared.profile.max_frequency();
                            let recipe = if types.iter().all(Option::is_some) && rate_ok {
                                let id = next_output;
                                next_output += 1;
                                let variables = names.iter().cloned().zip(types.iter().flatten().copied()).collect();
                                outputs = Some((id, variables, Duration::from_secs_f64(1.0 / frequency)));
                                id
                            } else {
                                0
                            };
                            replies.push(Reply::OutputsSetUp {
                                recipe,
                                types: types.iter().map(|t| t.map_or("NOT_FOUND", RtdeType::name).to_owned()).collect(),
                            });
                        }
                        Request::SetupInputs { names } => {
                            let names = named(names);
                            let types: Vec<Option<RtdeType>> =
                                names.iter().map(|name| input_type(name)).collect();
                            let recipe = if types.iter().all(Option::is_some) {
                                let id = next_input;
                                next_input += 1;
                                inputs.insert(id, names.iter().cloned().zip(types.iter().flatten().copied()).collect());
                                id
                            } else {
                                0
                            };
                            replies.push(Reply::InputsSetUp {
                                recipe,
                                types: types.iter().map(|t| t.map_or("NOT_FOUND", RtdeType::name).to_owned()).collect(),
                            });
                        }
                        Request::Start => {
                            let period = outputs.as_ref().map(|(_, _, period)| *period);
                            streaming = period.map(tokio::time::interval);
                            replies.push(Reply::Started { accepted: period.is_some() });
                        }
                        Request::Pause => {
                            streaming = None;
                            replies.push(Reply::Paused { accepted: true });
                        }
                        Request::Data { recipe, payload } => {
                            let Some(variables) = inputs.get(&recipe) else { continue };
                            let recipe = yarok_hw::ur::rtde::Recipe { id: recipe, variables: variables.clone() };
                            if let Ok(values) = recipe.decode(&payload) {
                                let mut known = shared.inputs.lock().unwrap();
                                for ((name, _), value) in recipe.variables.iter().zip(values) {
                                    known.insert(name.clone(), value);
                                }
                            }
                        }
                        _ => {}
                    }
                }
            }
            _ = tick => {
                if let Some((id, variables, _)) = &outputs {
                    let mut payload = Vec::new();
                    for (name, rtde_type) in variables {
                        shared.output(name, *rtde_type).encode(&mut payload);
                    }
                    replies.push(Reply::Data { recipe: *id, payload });
                }
            }
        }
        for reply in replies {
            if writer.write_all(&reply.encode().unwrap()).await.is_err() {
                return;
            }
        }
    }
}

impl Shared {
    /// The dashboard's reply to `command`, as a controller of the profile answers it.
    fn dashboard(&self, command: &str) -> String {
        let mut arm = self.arm.lock().unwrap();
        let e_series = self.profile == Profile::ESeries;
        match command {
            "PolyscopeVersion" => self.profile.polyscope(),
            "get serial number" => "20185500020".into(),
            "is in remote control" if e_series => "true".into(),
            "robotmode" => format!("Robotmode: {}", arm.robot_mode),
            "safetystatus" if e_series => format!("Safetystatus: {}", arm.safety),
            "safetymode" => format!("Safetymode: {}", arm.safety),
            "power on" => {
                arm.robot_mode = "IDLE";
                "Powering on".into()
            }
            "power off" => {
                arm.robot_mode = "POWER_OFF";
                "Powering off".into()
            }
            "brake release" => {
                arm.robot_mode = "RUNNING";
                "Brake releasing".into()
            }
            "unlock protective stop" => match arm.stopped_at {
                Some(at) if at.elapsed() < Duration::from_secs(5) => {
                    "Cannot unlock protective stop until 5s after occurrence. Always inspect \
                     cause of protective stop before unlocking"
                        .into()
                }
                _ => {
                    arm.safety = "NORMAL";
                    arm.stopped_at = None;
                    "Protective stop releasing".into()
                }
            },
            "close safety popup" => "closing safety popup".into(),
            "play" if arm.program.is_some() && arm.safety == "NORMAL" => {
                arm.playing = true;
                "Starting program".into()
            }
            "play" => "Failed to execute: play".into(),
            "stop" => {
                arm.playing = false;
                "Stopped".into()
            }
            _ => match command.strip_prefix("load ") {
                Some(program) if program.ends_with(".urp") => {
                    arm.program = Some(program.to_owned());
                    format!("Loading program: {program}")
                }
                Some(program) => format!("File not found: {program}"),
                None => format!("Could not understand: '{command}'"),
            },
        }
    }
}

/// One client's dashboard session.
async fn serve_dashboard(stream: TcpStream, shared: Arc<Shared>) {
    let (reader, mut writer) = stream.into_split();
    let welcome = "Connected: Universal Robots Dashboard Server\n";
    if writer.write_all(welcome.as_bytes()).await.is_err() {
        return;
    }
    let mut lines = tokio::io::BufReader::new(reader).lines();
    while let Ok(Some(command)) = lines.next_line().await {
        let command = command.trim();
        if command == "quit" {
            let _ = writer.write_all(b"Disconnected\n").await;
            return;
        }
        let reply = format!("{}\n", shared.dashboard(command));
        if writer.write_all(reply.as_bytes()).await.is_err() {
            return;
        }
    }
}

impl Shared {
    /// The gripper socket's reply to `command`.
    fn gripper(&self, command: &str) -> String {
        let mut fingers = self.fingers.lock().unwrap();
        let now = Instant::now();
        fingers.update(now);
        let words: Vec<&str> = command.split_whitespace().collect();
        match words.as_slice() {
            ["GET", name] => {
                let value = match *name {
                    "ACT" => fingers.act,
                    "GTO" => fingers.gto,
                    "STA" => fingers.sta,
                    "FLT" => fingers.flt,
                    "OBJ" => fingers.obj,
                    "PRE" => fingers.pre,
                    "POS" => fingers.position(),
                    "SPE" => fingers.speed,
                    "FOR" => fingers.force,
                    _ => return "?".into(),
                };
                format!("{name} {value}")
            }
            ["SET", pairs @ ..] if !pairs.is_empty() && pairs.len() % 2 == 0 => {
                fingers.commands.push(command.to_owned());
                for pair in pairs.chunks(2) {
                    let Ok(value) = pair[1].parse::<u8>() else {
                        return "?".into();
                    };
                    match pair[0] {
                        "ACT" if value == 0 => {
                            fingers.act = 0;
                            fingers.sta = 0;
                            fingers.gto = 0;
                            fingers.flt = 0;
                            fingers.activating_since = None;
                        }
                        "ACT" => {
                            fingers.act = 1;
                            if fingers.sta == 0 {
                                fingers.sta = 1;
                                fingers.activating_since = Some(now);
                            }
                        }
                        "POS" => fingers.target = value,
                        "SPE" => fingers.speed = value,
                        "FOR" => fingers.force = value,
                        "GTO" => {
                            fingers.gto = value;
                            if value == 1 && fingers.sta == 3 {
                                fingers.pre = fingers.target;
                                fingers.obj = 0;
                            } else if value == 1 {
                                fingers.flt = 5;
                            }
                        }
                        _ => {}
                    }
                }
                "ack".into()
            }
            _ => "?".into(),
        }
    }
}

/// One client's gripper socket session.
async fn serve_gripper(stream: TcpStream, shared: Arc<Shared>) {
    let (reader, mut writer) = stream.into_split();
    let mut lines = tokio::io::BufReader::new(reader).lines();
    while let Ok(Some(command)) = lines.next_line().await {
        let reply = format!("{}\n", shared.gripper(command.trim()));
        if writer.write_all(reply.as_bytes()).await.is_err() {
            return;
        }
    }
}
