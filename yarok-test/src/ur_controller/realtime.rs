//! The fake controller's real-time interface (port 30003): `int32 size` and 139 doubles (the
//! 1116-byte layout of 3.10+ and 5.x) at 125 Hz on CB3, 500 Hz on e-Series; script lines sent
//! to it run as on the secondary interface.

use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Duration;

use tokio::io::{AsyncBufReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

use super::motion::ArmState;
use super::{Profile, Shared};

/// Doubles in the 3.10+ / 5.x packet.
const DOUBLES: usize = 139;

/// Where fields start, in doubles.
const Q_TARGET: usize = 1;
const Q_ACTUAL: usize = 31;
const QD_ACTUAL: usize = 37;
const ROBOT_MODE: usize = 94;
const JOINT_MODES: usize = 95;
const SAFETY_MODE: usize = 101;
const SPEED_SCALING: usize = 117;
const PROGRAM_STATE: usize = 131;
const SAFETY_STATUS: usize = 138;

impl Shared {
    /// A real-time packet now.
    fn realtime_packet(&self) -> Vec<u8> {
        let ArmState {
            q,
            qd,
            target,
            moving,
        } = self.motion.lock().unwrap().state();
        let safety = if self.arm.lock().unwrap().safety == "NORMAL" {
            1.0
        } else {
            3.0
        };
        let mut values = [0.0f64; DOUBLES];
        values[0] = self.started.elapsed().as_secs_f64();
        values[Q_TARGET..Q_TARGET + 6].copy_from_slice(&target);
        values[Q_ACTUAL..Q_ACTUAL + 6].copy_from_slice(&q);
        values[QD_ACTUAL..QD_ACTUAL + 6].copy_from_slice(&qd);
        values[ROBOT_MODE] = f64::from(self.robot_mode());
        values[JOINT_MODES..JOINT_MODES + 6].fill(253.0);
        values[SAFETY_MODE] = safety;
        values[SPEED_SCALING] = 1.0;
        values[PROGRAM_STATE] = if moving { 2.0 } else { 1.0 };
        values[SAFETY_STATUS] = safety;
        let mut packet = ((4 + 8 * DOUBLES) as i32).to_be_bytes().to_vec();
        for value in values {
            packet.extend(value.to_be_bytes());
        }
        packet
    }
}

/// One client's real-time session.
pub(super) async fn serve_realtime(stream: TcpStream, shared: Arc<Shared>) {
    let drops = shared.drops.load(Ordering::Relaxed);
    let (reader, mut writer) = stream.into_split();
    let mut lines = tokio::io::BufReader::new(reader).lines();
    let hz = if shared.profile == Profile::ESeries {
        500.0
    } else {
        125.0
    };
    let mut packets = tokio::time::interval(Duration::from_secs_f64(1.0 / hz));
    loop {
        tokio::select! {
            line = lines.next_line() => match line {
                Ok(Some(line)) => shared.run_script(&line),
                _ => return,
            },
            _ = packets.tick() => {
                if shared.drops.load(Ordering::Relaxed) != drops
                    || writer.write_all(&shared.realtime_packet()).await.is_err()
                {
                    return;
                }
            }
        }
    }
}
