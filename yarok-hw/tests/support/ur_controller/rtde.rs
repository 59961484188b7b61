//! The fake controller's RTDE server.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use yarok_hw::ur::rtde::{Reply, Request, RtdeType, Value, input_type, output_type, take_frame};

use super::Shared;

impl Shared {
    /// The output variable `name`'s value now.
    fn output(&self, name: &str, rtde_type: RtdeType) -> Value {
        match name {
            "timestamp" => Value::Double(self.started.elapsed().as_secs_f64()),
            "actual_q" => Value::Vector6d(self.joints.lock().unwrap().now(Instant::now())),
            "target_q" => Value::Vector6d(self.joints.lock().unwrap().target()),
            "robot_mode" => Value::Int32(i32::from(self.robot_mode())),
            "safety_mode" | "safety_status" => {
                Value::Int32(match self.arm.lock().unwrap().safety {
                    "NORMAL" => 1,
                    "PROTECTIVE_STOP" => 3,
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

/// An output recipe being streamed: its id, variables and period.
type Outputs = (u8, Vec<(String, RtdeType)>, Duration);

/// One client's RTDE session.
pub(super) async fn serve_rtde(stream: TcpStream, shared: Arc<Shared>) {
    let drops = shared.drops.load(Ordering::Relaxed);
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
                if shared.drops.load(Ordering::Relaxed) != drops {
                    return;
                }
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
