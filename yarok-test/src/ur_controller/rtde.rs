//! The fake controller's RTDE server.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use std::io::{Read, Write};
use std::sync::Mutex;
use std::sync::atomic::AtomicBool;
use yarok_hw::ur::rtde::{Reply, Request, RtdeType, Value, input_type, output_type, take_frame};

use super::Shared;

impl Shared {
    /// The output variable `name`'s value now.
    fn output(&self, name: &str, rtde_type: RtdeType) -> Value {
        match name {
            "timestamp" => Value::Double(self.started.elapsed().as_secs_f64()),
            "actual_q" => Value::Vector6d(self.motion.lock().unwrap().state().q),
            "actual_qd" => Value::Vector6d(self.motion.lock().unwrap().state().qd),
            "target_q" => Value::Vector6d(self.motion.lock().unwrap().state().target),
            "robot_mode" => Value::Int32(i32::from(self.robot_mode())),
            "safety_mode" | "safety_status" => {
                Value::Int32(match self.arm.lock().unwrap().safety {
                    "NORMAL" => 1,
                    "PROTECTIVE_STOP" => 3,
                    "ROBOT_EMERGENCY_STOP" => 7,
                    _ => 9,
                })
            }
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

/// An output recipe being streamed: its id, variables (shared, so that the streamer takes them
/// each package without copying the names) and period.
type Outputs = (u8, Arc<[(String, RtdeType)]>, Duration);

/// What an RTDE session's reader and streamer share.
struct Session {
    writer: Mutex<std::net::TcpStream>,
    outputs: Mutex<Option<Outputs>>,
    streaming: AtomicBool,
    ended: AtomicBool,
}

impl Session {
    fn send(&self, reply: &Reply) -> bool {
        self.writer
            .lock()
            .unwrap()
            .write_all(&reply.encode().unwrap())
            .is_ok()
    }
}

/// One client's RTDE session, on threads of its own: its requests answered on this one, and
/// its data packages sent on another at the recipe's rate, each at its due time to within tens
/// of microseconds (as a controller's real-time loop sends them; tokio's timer would add a
/// millisecond).
pub(super) fn serve_rtde(stream: std::net::TcpStream, shared: Arc<Shared>) {
    let Ok(writer) = stream.try_clone() else {
        return;
    };
    let _ = stream.set_read_timeout(Some(Duration::from_millis(50)));
    let _ = stream.set_nodelay(true);
    let session = Arc::new(Session {
        writer: Mutex::new(writer),
        outputs: Mutex::new(None),
        streaming: AtomicBool::new(false),
        ended: AtomicBool::new(false),
    });
    let drops = shared.drops.load(Ordering::Relaxed);
    let streamer = {
        let (session, shared) = (Arc::clone(&session), Arc::clone(&shared));
        std::thread::spawn(move || stream_outputs(&session, &shared))
    };
    read_requests(stream, &session, &shared, drops);
    session.ended.store(true, Ordering::Relaxed);
    let _ = streamer.join();
}

/// Answers requests until the client leaves, the fake closes, or a drop is asked for.
fn read_requests(mut stream: std::net::TcpStream, session: &Session, shared: &Shared, drops: u32) {
    let mut buffer = Vec::new();
    let mut inputs: HashMap<u8, Vec<(String, RtdeType)>> = HashMap::new();
    let (mut next_output, mut next_input) = (1u8, 1u8);
    let mut chunk = [0u8; 4096];
    loop {
        if shared.drops.load(Ordering::Relaxed) != drops || shared.closed.load(Ordering::Relaxed) {
            let _ = stream.shutdown(std::net::Shutdown::Both);
            return;
        }
        match stream.read(&mut chunk) {
            Ok(0) => return,
            Ok(read) => buffer.extend_from_slice(&chunk[..read]),
            Err(error)
                if matches!(
                    error.kind(),
                    std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                ) =>
            {
                continue;
            }
            Err(_) => return,
        }
        while let Ok(Some((kind, body))) = take_frame(&mut buffer) {
            let Ok(request) = Request::decode(kind, &body) else {
                return;
            };
            let reply = match request {
                Request::ProtocolVersion(version) => Reply::ProtocolVersion {
                    accepted: version == 2,
                },
                Request::ControllerVersion => Reply::ControllerVersion(shared.profile.version()),
                Request::SetupOutputs { frequency, names } => {
                    let names = named(names);
                    shared.asked.lock().unwrap().extend(names.iter().cloned());
                    let types: Vec<Option<RtdeType>> =
                        names.iter().map(|name| output_type(name)).collect();
                    let rate_ok = frequency > 0.0 && frequency <= shared.profile.max_frequency();
                    let recipe = if types.iter().all(Option::is_some) && rate_ok {
                        let id = next_output;
                        next_output += 1;
                        let variables: Arc<[(String, RtdeType)]> = names
                            .iter()
                            .cloned()
                            .zip(types.iter().flatten().copied())
                            .collect();
                        *session.outputs.lock().unwrap() =
                            Some((id, variables, Duration::from_secs_f64(1.0 / frequency)));
                        id
                    } else {
                        0
                    };
                    Reply::OutputsSetUp {
                        recipe,
                        types: types
                            .iter()
                            .map(|t| t.map_or("NOT_FOUND", RtdeType::name).to_owned())
                            .collect(),
                    }
                }
                Request::SetupInputs { names } => {
                    let names = named(names);
                    let types: Vec<Option<RtdeType>> =
                        names.iter().map(|name| input_type(name)).collect();
                    let recipe = if types.iter().all(Option::is_some) {
                        let id = next_input;
                        next_input += 1;
                        inputs.insert(
                            id,
                            names
                                .iter()
                                .cloned()
                                .zip(types.iter().flatten().copied())
                                .collect(),
                        );
                        id
                    } else {
                        0
                    };
                    Reply::InputsSetUp {
                        recipe,
                        types: types
                            .iter()
                            .map(|t| t.map_or("NOT_FOUND", RtdeType::name).to_owned())
                            .collect(),
                    }
                }
                Request::Start => {
                    let accepted = session.outputs.lock().unwrap().is_some();
                    session.streaming.store(accepted, Ordering::Relaxed);
                    Reply::Started { accepted }
                }
                Request::Pause => {
                    session.streaming.store(false, Ordering::Relaxed);
                    Reply::Paused { accepted: true }
                }
                Request::Data { recipe, payload } => {
                    if let Some(variables) = inputs.get(&recipe) {
                        let recipe = yarok_hw::ur::rtde::Recipe {
                            id: recipe,
                            variables: variables.clone(),
                        };
                        if let Ok(values) = recipe.decode(&payload) {
                            let mut known = shared.inputs.lock().unwrap();
                            for ((name, _), value) in recipe.variables.iter().zip(values) {
                                known.insert(name.clone(), value);
                            }
                        }
                    }
                    continue;
                }
                _ => continue,
            };
            if !session.send(&reply) {
                return;
            }
        }
    }
}

/// Sends the output recipe's packages at its rate while streaming, until the session ends.
fn stream_outputs(session: &Session, shared: &Shared) {
    let mut due = Instant::now();
    while !session.ended.load(Ordering::Relaxed) {
        let outputs = session.outputs.lock().unwrap().clone();
        let streaming =
            session.streaming.load(Ordering::Relaxed) && !shared.rtde_mute.load(Ordering::Relaxed);
        let (Some((id, variables, period)), true) = (outputs, streaming) else {
            std::thread::sleep(Duration::from_millis(1));
            due = Instant::now();
            continue;
        };
        // Sleep to just before the due time, then spin: sleeps overshoot by tens of µs.
        let now = Instant::now();
        if due > now + SPIN {
            std::thread::sleep(due - now - SPIN);
        }
        while Instant::now() < due {
            std::hint::spin_loop();
        }
        let mut payload = Vec::new();
        for (name, rtde_type) in variables.iter() {
            shared.output(name, *rtde_type).encode(&mut payload);
        }
        if !session.send(&Reply::Data {
            recipe: id,
            payload,
        }) {
            return;
        }
        due += period;
        // A client that stalls the socket does not make the fake send bursts later.
        if due + period < Instant::now() {
            due = Instant::now() + period;
        }
    }
}

/// How long before a package is due its sender stops sleeping and spins.
const SPIN: Duration = Duration::from_micros(300);
