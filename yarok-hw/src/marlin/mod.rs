//! Marlin G-code over any byte transport: the protocol ([`Reply`], [`numbered_line`]) and the
//! driver ([`Marlin`]).

mod driver;
mod error;
mod line;
mod reply;

pub use driver::{Answer, Marlin, MarlinSettings};
pub use error::MarlinError;
pub use line::numbered_line;
pub use reply::{Position, Reply};
