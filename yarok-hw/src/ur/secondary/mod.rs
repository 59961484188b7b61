//! The primary and secondary interfaces (ports 30001/30002): robot-state packets
//! ([`take_packet`], [`parse`]) and a client ([`Secondary`]) that reads them and sends URScript.

mod client;
mod packet;

pub use client::{Secondary, SecondaryError, send_script, send_script_and_close};
pub use packet::{
    CartesianInfo, JointData, KinematicsInfo, MAX_PACKET, Packet, PacketError, RobotModeData,
    RobotState, VersionMessage, parse, take_packet,
};
