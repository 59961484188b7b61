//! Universal Robots controllers: RTDE ([`rtde`]), the interface that streams the arm's state at
//! 125 Hz (CB3) or 500 Hz (e-Series) and takes inputs.

pub mod rtde;
