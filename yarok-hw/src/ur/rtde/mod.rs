//! RTDE, the UR controller's real-time data exchange on port 30004: the messages
//! ([`Request`], [`Reply`]) and their framing ([`take_frame`]), typed values and recipes
//! ([`Value`], [`Recipe`]), the controller's variables ([`output_type`], [`input_type`]), and an
//! async client ([`Rtde`]).

mod client;
mod message;
mod value;
mod variables;

pub use client::{Rtde, RtdeError, RtdeSettings};
pub use message::{ControllerVersion, MAX_MESSAGE, MessageError, Reply, Request, Text, take_frame};
pub use value::{Recipe, RecipeError, RtdeType, Value};
pub use variables::{input_type, output_type};
