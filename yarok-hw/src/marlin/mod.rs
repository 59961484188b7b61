//! Marlin G-code over any byte transport: the protocol ([`Reply`], [`numbered_line`]) and the
//! driver ([`Marlin`]), and [`Reconnecting`] for printers that are unplugged and come back.

mod driver;
mod error;
mod line;
mod reconnect;
mod reply;

pub use driver::{Answer, HANDSHAKE_RETRY, Marlin, MarlinSettings};
pub use error::MarlinError;
pub use line::numbered_line;
pub use reconnect::Reconnecting;
pub use reply::{Position, Reply};
