//! Tactile sensors in the world: components whose images come from the [`crate::tactile`]
//! optical models over the depth their internal cameras render.

mod calibrated;
mod component;
mod digit;
mod flat_gel;
mod gelsight;
mod geltip;
mod kind;
mod mock;
mod modelled;
mod phong;
#[cfg(feature = "camera")]
mod real;
mod sensor;
#[cfg(feature = "render")]
mod sim;

pub use component::{Tactile, TactileKind};
pub use digit::{Digit, DigitKind};
pub use gelsight::{GelSight2014, GelSight2014Kind};
pub use geltip::{GelTip, GelTipKind};
pub use sensor::{Contact, GelContact, TactileError, TactileSensor};
