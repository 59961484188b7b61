//! Robots: the Anet A30 printer used as a cartesian robot, the Universal Robots arms, and any
//! serial arm in MJCF.

mod anet_a30;
mod motion;
mod motions;
mod paths;
mod profile;
pub mod serial;
pub mod ur;

pub use anet_a30::{ARRIVED_MM, AnetA30, AxesDrive, WORK_VOLUME_MM};
pub use motion::Motion;
