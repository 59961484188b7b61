//! Robots: the Anet A30 printer used as a cartesian robot and the Universal Robots arms.

mod anet_a30;
pub mod ur;

pub use anet_a30::{ARRIVED_MM, AnetA30, WORK_VOLUME_MM};
