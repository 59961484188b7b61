//! Universal Robots controllers: RTDE ([`rtde`]), the interface that streams the arm's state at
//! 125 Hz (CB3) or 500 Hz (e-Series) and takes inputs; the secondary interface ([`secondary`]),
//! which sends robot states at 10 Hz and runs URScript (the motions' text: [`script`]); the
//! program a stream of targets runs as, with its protocol ([`external_control`]); and the
//! dashboard server ([`dashboard`]) that powers the arm, releases its brakes and unlocks
//! protective stops.

pub mod dashboard;
pub mod external_control;
pub mod rtde;
pub mod script;
pub mod secondary;
