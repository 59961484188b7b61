//! Packets of the primary and secondary interfaces (ports 30001/30002): `int32 size`
//! (big-endian, counting the 5-byte header), `uint8 type`, then the body. A robot state
//! (type 16) is a list of sub-packages with the same header; the ones read here are parsed by
//! their CB3 (3.x) and e-Series (5.x) layouts, the rest skipped by their length.

/// The largest packet accepted (real ones are about 1 kB).
pub const MAX_PACKET: usize = 1 << 16;

const HEADER: usize = 5;
const ROBOT_STATE: u8 = 16;
const ROBOT_MESSAGE: u8 = 20;
const VERSION_MESSAGE: i8 = 3;

/// A packet could not be framed or parsed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum PacketError {
    /// The size field is impossible (smaller than the header, or beyond [`MAX_PACKET`]).
    #[error("a packet size of {0} bytes is impossible")]
    Size(i32),
    /// A sub-package's size runs outside its packet.
    #[error("sub-package {kind} of {size} bytes does not fit its packet")]
    SubPackage {
        /// Its type.
        kind: u8,
        /// Its size field.
        size: i32,
    },
    /// A field runs past the end of its (sub-)package.
    #[error("a {what} of {got} bytes is too short (needs {needed})")]
    Truncated {
        /// What was read.
        what: &'static str,
        /// Bytes needed.
        needed: usize,
        /// Bytes there.
        got: usize,
    },
}

/// The arm's mode (sub-package 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotModeData {
    /// Controller time, µs.
    pub timestamp: u64,
    /// A real robot is connected (not the simulator).
    pub connected: bool,
    /// The robot is enabled.
    pub enabled: bool,
    /// The arm is powered.
    pub power_on: bool,
    /// An emergency stop is active.
    pub emergency_stopped: bool,
    /// A protective stop is active.
    pub protective_stopped: bool,
    /// A program (a sent script, a loaded program) runs.
    pub program_running: bool,
    /// The program is paused.
    pub program_paused: bool,
    /// 7 running, 5 idle, 3 power off, …
    pub robot_mode: u8,
    /// 0 position, 1 teach, 2 force, 3 torque.
    pub control_mode: u8,
    /// The speed slider.
    pub target_speed_fraction: f64,
    /// The speed scaling the safety system applies.
    pub speed_scaling: f64,
}

/// One joint (sub-package 1 holds six).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointData {
    /// Position, rad.
    pub q_actual: f64,
    /// Target position, rad.
    pub q_target: f64,
    /// Velocity, rad/s.
    pub qd_actual: f64,
    /// Current, A.
    pub current: f32,
    /// Voltage, V.
    pub voltage: f32,
    /// Motor temperature, °C.
    pub motor_temperature: f32,
    /// 253 running, 255 idle, …
    pub mode: u8,
}

/// The tool centre point (sub-package 4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartesianInfo {
    /// `x, y, z` (m) and a rotation vector (rad), in the base frame.
    pub tcp_pose: [f64; 6],
    /// The TCP's offset from the flange, the same way.
    pub tcp_offset: [f64; 6],
}

/// The arm's calibrated kinematics (sub-package 5): its DH parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicsInfo {
    /// Per-joint calibration checksums.
    pub checksums: [u32; 6],
    /// DH θ offsets, rad.
    pub dh_theta: [f64; 6],
    /// DH a, m.
    pub dh_a: [f64; 6],
    /// DH d, m.
    pub dh_d: [f64; 6],
    /// DH α, rad.
    pub dh_alpha: [f64; 6],
}

/// A robot state (packet type 16): the sub-packages read, each when present.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RobotState {
    /// Sub-package 0.
    pub mode: Option<RobotModeData>,
    /// Sub-package 1.
    pub joints: Option<[JointData; 6]>,
    /// Sub-package 4.
    pub cartesian: Option<CartesianInfo>,
    /// Sub-package 5.
    pub kinematics: Option<KinematicsInfo>,
}

/// The controller's version message, sent first on connect.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VersionMessage {
    /// `URControl`.
    pub project: String,
    /// Major version.
    pub major: u8,
    /// Minor version.
    pub minor: u8,
    /// Bug-fix version.
    pub bugfix: i32,
    /// Build number.
    pub build: i32,
    /// When it was built.
    pub build_date: String,
}

/// A packet of the primary or secondary interface.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Packet {
    /// Type 16.
    RobotState(Box<RobotState>),
    /// Type 20, a version message.
    Version(VersionMessage),
    /// Any other packet (other robot messages, program state, …), by type.
    Other(u8),
}

/// The first whole packet at the front of `buffer`, removed from it; `None` while it is still
/// incomplete.
///
/// # Errors
///
/// [`PacketError::Size`] when the size field is impossible (the stream is out of step).
pub fn take_packet(buffer: &mut Vec<u8>) -> Result<Option<Vec<u8>>, PacketError> {
    let Some(header) = buffer.get(..4) else {
        return Ok(None);
    };
    let size = i32::from_be_bytes(header.try_into().expect("4 bytes"));
    let length = usize::try_from(size)
        .ok()
        .filter(|length| (HEADER..=MAX_PACKET).contains(length))
        .ok_or(PacketError::Size(size))?;
    if buffer.len() < length {
        return Ok(None);
    }
    Ok(Some(buffer.drain(..length).collect()))
}

/// Reads big-endian fields from the front of a slice.
struct Fields<'a> {
    bytes: &'a [u8],
    what: &'static str,
}

impl<'a> Fields<'a> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], PacketError> {
        match self.bytes.split_first_chunk::<N>() {
            Some((first, rest)) => {
                self.bytes = rest;
                Ok(*first)
            }
            None => Err(PacketError::Truncated {
                what: self.what,
                needed: N,
                got: self.bytes.len(),
            }),
        }
    }
    fn u8(&mut self) -> Result<u8, PacketError> {
        Ok(self.take::<1>()?[0])
    }
    fn flag(&mut self) -> Result<bool, PacketError> {
        Ok(self.u8()? != 0)
    }
    fn u32(&mut self) -> Result<u32, PacketError> {
        Ok(u32::from_be_bytes(self.take()?))
    }
    fn i32(&mut self) -> Result<i32, PacketError> {
        Ok(i32::from_be_bytes(self.take()?))
    }
    fn u64(&mut self) -> Result<u64, PacketError> {
        Ok(u64::from_be_bytes(self.take()?))
    }
    fn f32(&mut self) -> Result<f32, PacketError> {
        Ok(f32::from_be_bytes(self.take()?))
    }
    fn f64(&mut self) -> Result<f64, PacketError> {
        Ok(f64::from_be_bytes(self.take()?))
    }
    fn six(&mut self) -> Result<[f64; 6], PacketError> {
        let mut values = [0.0; 6];
        for value in &mut values {
            *value = self.f64()?;
        }
        Ok(values)
    }
    fn text(&mut self, length: usize) -> Result<String, PacketError> {
        if self.bytes.len() < length {
            return Err(PacketError::Truncated {
                what: self.what,
                needed: length,
                got: self.bytes.len(),
            });
        }
        let (text, rest) = self.bytes.split_at(length);
        self.bytes = rest;
        Ok(String::from_utf8_lossy(text).into_owned())
    }
}

/// Parses a whole packet (header included, as [`take_packet`] gives it).
///
/// # Errors
///
/// [`PacketError`] for a malformed packet or sub-package.
pub fn parse(packet: &[u8]) -> Result<Packet, PacketError> {
    let mut header = Fields {
        bytes: packet,
        what: "packet header",
    };
    let _size = header.i32()?;
    let kind = header.u8()?;
    let body = header.bytes;
    match kind {
        ROBOT_STATE => robot_state(body).map(|state| Packet::RobotState(Box::new(state))),
        ROBOT_MESSAGE => robot_message(body),
        other => Ok(Packet::Other(other)),
    }
}

fn robot_state(mut body: &[u8]) -> Result<RobotState, PacketError> {
    let mut state = RobotState::default();
    while !body.is_empty() {
        let mut header = Fields {
            bytes: body,
            what: "sub-package header",
        };
        let size = header.i32()?;
        let kind = header.u8()?;
        let length = usize::try_from(size)
            .ok()
            .filter(|length| (HEADER..=body.len()).contains(length))
            .ok_or(PacketError::SubPackage { kind, size })?;
        let content = &body[HEADER..length];
        body = &body[length..];
        match kind {
            0 => state.mode = Some(robot_mode(content)?),
            1 => state.joints = Some(joints(content)?),
            4 => state.cartesian = Some(cartesian(content)?),
            5 => state.kinematics = Some(kinematics(content)?),
            _ => {}
        }
    }
    Ok(state)
}

/// RobotModeData from 3.2 on (3.x: 41 bytes after the header; 5.x adds a byte, ignored).
fn robot_mode(content: &[u8]) -> Result<RobotModeData, PacketError> {
    let mut f = Fields {
        bytes: content,
        what: "robot mode sub-package",
    };
    Ok(RobotModeData {
        timestamp: f.u64()?,
        connected: f.flag()?,
        enabled: f.flag()?,
        power_on: f.flag()?,
        emergency_stopped: f.flag()?,
        protective_stopped: f.flag()?,
        program_running: f.flag()?,
        program_paused: f.flag()?,
        robot_mode: f.u8()?,
        control_mode: f.u8()?,
        target_speed_fraction: f.f64()?,
        speed_scaling: f.f64()?,
    })
}

fn joints(content: &[u8]) -> Result<[JointData; 6], PacketError> {
    let mut f = Fields {
        bytes: content,
        what: "joint sub-package",
    };
    let mut joint = || -> Result<JointData, PacketError> {
        let joint = JointData {
            q_actual: f.f64()?,
            q_target: f.f64()?,
            qd_actual: f.f64()?,
            current: f.f32()?,
            voltage: f.f32()?,
            motor_temperature: f.f32()?,
            mode: {
                let _micro_temperature = f.f32()?;
                f.u8()?
            },
        };
        Ok(joint)
    };
    Ok([joint()?, joint()?, joint()?, joint()?, joint()?, joint()?])
}

fn cartesian(content: &[u8]) -> Result<CartesianInfo, PacketError> {
    let mut f = Fields {
        bytes: content,
        what: "cartesian sub-package",
    };
    Ok(CartesianInfo {
        tcp_pose: f.six()?,
        tcp_offset: f.six()?,
    })
}

fn kinematics(content: &[u8]) -> Result<KinematicsInfo, PacketError> {
    let mut f = Fields {
        bytes: content,
        what: "kinematics sub-package",
    };
    let mut checksums = [0; 6];
    for checksum in &mut checksums {
        *checksum = f.u32()?;
    }
    Ok(KinematicsInfo {
        checksums,
        dh_theta: f.six()?,
        dh_a: f.six()?,
        dh_d: f.six()?,
        dh_alpha: f.six()?,
    })
}

fn robot_message(body: &[u8]) -> Result<Packet, PacketError> {
    let mut f = Fields {
        bytes: body,
        what: "robot message",
    };
    let _timestamp = f.u64()?;
    let _source = f.u8()?;
    if f.u8()? as i8 != VERSION_MESSAGE {
        return Ok(Packet::Other(ROBOT_MESSAGE));
    }
    let name_length = usize::from(f.u8()?);
    let project = f.text(name_length)?;
    let major = f.u8()?;
    let minor = f.u8()?;
    let bugfix = f.i32()?;
    let build = f.i32()?;
    let build_date = String::from_utf8_lossy(f.bytes).into_owned();
    Ok(Packet::Version(VersionMessage {
        project,
        major,
        minor,
        bugfix,
        build,
        build_date,
    }))
}
