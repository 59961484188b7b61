//! The dashboard's and the gripper socket's replies are parsed from whatever a peer sends:
//! 100 000 generated reply lines — fragments of every real reply, numbers, separators,
//! arbitrary and non-UTF-8 bytes — each answered to a command, never a panic, and every reply
//! either understood as what it says or refused as an error naming the peer.

use std::time::Duration;

use tokio::io::{AsyncBufReadExt, AsyncWriteExt, BufReader, DuplexStream};
use yarok_hw::robotiq::{Gripper, GripperError};
use yarok_hw::ur::dashboard::{Dashboard, DashboardError, RobotMode};

use yarok_test::generator;

use generator::Generator;

/// Reply lines from the generator.
trait ReplyLines {
    fn line(&mut self) -> Vec<u8>;
}

impl ReplyLines for Generator {
    /// A reply line, without its ending.
    fn line(&mut self) -> Vec<u8> {
        let parts = [
            "Robotmode: ",
            "RUNNING",
            "POWER_OFF",
            "POS",
            "OBJ",
            " ",
            "  ",
            "ack",
            "255",
            "-1",
            "300",
            "abc",
            "Safetystatus: ",
            "é",
            "\r",
            "POS 12",
            "1e3",
            "",
        ];
        let mut line = Vec::new();
        for _ in 0..(self.next_u64() % 5) {
            line.extend_from_slice(self.pick(&parts).as_bytes());
        }
        if self.next_u64().is_multiple_of(9) {
            line.push(self.next_u64() as u8 | 0x80);
        }
        line.retain(|byte| *byte != b'\n');
        line
    }
}

const ROUNDS: usize = 50_000;

/// A peer that sends `welcome`, then answers each command line with the next of `replies`.
async fn answer(peer: DuplexStream, welcome: &'static [u8], replies: Vec<Vec<u8>>) {
    let (reader, mut writer) = tokio::io::split(peer);
    writer.write_all(welcome).await.unwrap();
    let mut lines = BufReader::new(reader).lines();
    for reply in replies {
        if lines.next_line().await.unwrap().is_none() {
            return;
        }
        writer
            .write_all(&[reply.as_slice(), b"\n"].concat())
            .await
            .unwrap();
    }
}

#[tokio::test(start_paused = true)]
async fn a_hundred_thousand_generated_replies_never_panic() {
    // The dashboard: a welcome, then a generated reply to every `robotmode`.
    let (ours, theirs) = tokio::io::duplex(1 << 16);
    let mut generator = Generator(0x9E37_79B9_7F4A_7C15);
    let replies: Vec<Vec<u8>> = (0..ROUNDS).map(|_| generator.line()).collect();
    let welcome = b"Connected: Universal Robots Dashboard Server\n";
    let server = tokio::spawn(answer(theirs, welcome, replies));
    let mut dashboard = Dashboard::connect(ours, "dash-test", Duration::from_secs(1))
        .await
        .unwrap();
    let mut understood = 0;
    for _ in 0..ROUNDS {
        match dashboard.robot_mode().await {
            Ok(RobotMode::Running | RobotMode::PowerOff) => understood += 1,
            Ok(_) => {}
            Err(DashboardError::Failed { controller, .. }) => assert_eq!(controller, "dash-test"),
            Err(other) => panic!("{other}"),
        }
    }
    server.await.unwrap();
    assert!(understood > 100, "{understood}");

    // The gripper socket: a generated reply to every `GET POS`.
    let (ours, theirs) = tokio::io::duplex(1 << 16);
    let replies: Vec<Vec<u8>> = (0..ROUNDS).map(|_| generator.line()).collect();
    // What each reply says, read independently: `POS` and a value 0–255, spaces around.
    let expected: Vec<Option<u8>> = replies
        .iter()
        .map(|reply| {
            let text = String::from_utf8_lossy(reply);
            let value = text.trim().strip_prefix("POS")?.strip_prefix(' ')?;
            value.trim().parse().ok()
        })
        .collect();
    let server = tokio::spawn(answer(theirs, b"", replies));
    let mut gripper = Gripper::new(ours, "gripper-test", Duration::from_secs(1));
    let mut positions = 0;
    for expected in expected {
        match gripper.get("POS").await {
            Ok(position) => {
                assert_eq!(Some(position), expected);
                positions += 1;
            }
            Err(GripperError::Unexpected { gripper, .. }) => {
                assert_eq!(expected, None);
                assert_eq!(gripper, "gripper-test");
            }
            Err(other) => panic!("{other}"),
        }
    }
    server.await.unwrap();
    assert!(positions > 10, "{positions}");
}
