//! The fake controller's dashboard server.

use std::sync::Arc;
use std::time::Duration;

use tokio::io::{AsyncBufReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

use super::{Profile, Shared};

impl Shared {
    /// The dashboard's reply to `command`, as a controller of the profile answers it.
    fn dashboard(&self, command: &str) -> String {
        let mut arm = self.arm.lock().unwrap();
        let e_series = self.profile == Profile::ESeries;
        match command {
            "PolyscopeVersion" => self.profile.polyscope(),
            "get serial number" => "20185500020".into(),
            "is in remote control" if e_series => arm.remote_control.to_string(),
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
pub(super) async fn serve_dashboard(stream: TcpStream, shared: Arc<Shared>) {
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
        let delay = *shared.dashboard_delay.lock().unwrap();
        tokio::time::sleep(delay).await;
        let reply = format!("{}\n", shared.dashboard(command));
        if writer.write_all(reply.as_bytes()).await.is_err() {
            return;
        }
    }
}
