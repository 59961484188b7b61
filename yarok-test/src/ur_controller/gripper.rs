//! The fake controller's Robotiq URCap gripper socket.

use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use tokio::io::{AsyncBufReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

use super::Shared;

/// The gripper's registers and its fingers' motion.
#[derive(Debug, Clone)]
pub struct Fingers {
    act: u8,
    gto: u8,
    pub sta: u8,
    pub flt: u8,
    pub obj: u8,
    pub pre: u8,
    target: u8,
    speed: u8,
    pub force: u8,
    /// Finger position, 0 … 255, as a real number while moving.
    position: f64,
    activating_since: Option<Instant>,
    updated: Instant,
    /// Where closing fingers meet an object, if one is between them.
    pub object_at: Option<u8>,
    /// Every SET command, in order.
    pub commands: Vec<String>,
}

impl Fingers {
    /// A gripper after power-up: reset, open.
    pub(super) fn new() -> Self {
        Self {
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
        }
    }

    pub fn position(&self) -> u8 {
        self.position.round() as u8
    }

    /// Advances activation and motion to `now`.
    pub(super) fn update(&mut self, now: Instant) {
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
/// It ends when the fake is asked to drop its connections (checked every 20 ms).
pub(super) async fn serve_gripper(stream: TcpStream, shared: Arc<Shared>) {
    let drops = shared.drops.load(Ordering::Relaxed);
    let (reader, mut writer) = stream.into_split();
    let mut lines = tokio::io::BufReader::new(reader).lines();
    let mut check = tokio::time::interval(Duration::from_millis(20));
    loop {
        tokio::select! {
            line = lines.next_line() => {
                let Ok(Some(command)) = line else { return };
                if shared.gripper_mute.load(Ordering::Relaxed) {
                    continue;
                }
                let reply = format!("{}\n", shared.gripper(command.trim()));
                if writer.write_all(reply.as_bytes()).await.is_err() {
                    return;
                }
            }
            _ = check.tick() => {
                if shared.drops.load(Ordering::Relaxed) != drops {
                    return;
                }
            }
        }
    }
}
