//! [`Robotiq2f85`]: the Robotiq 2F-85 adaptive gripper, with the real gripper's requests and
//! status — position, speed and force 0–255, and `gOBJ`'s object detection.

use std::ops::Deref;

use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces, Mock};
use yarok_mjc::Sim;

use crate::grippers::parallel::{GripperNames, ParallelGripper, Stroke};

mod real;

/// The damping (tendon units) of the bundled template's servo unless configured.
const DAMPING: f64 = 2.0;

/// A Robotiq 2F-85 gripper: 85 mm stroke, position requests 0 (open) to 255 (closed) at a
/// speed and force 0–255 (20–150 mm/s; the least to the most squeeze), and the real gripper's
/// status: position, motion, and whether it stopped on an object before its request (`gOBJ`).
/// Its methods are a [`ParallelGripper`]'s.
///
/// Tag `robotiq_2f85`; mount it on an arm's flange (`<robotiq_2f85 name="gripper"
/// parent="flange"/>`). Bodies `left_pad` and `right_pad` (sites of the same names at the pad
/// faces) carry fingertip sensors; the site `pinch` is between the pads. Config `pad_friction`
/// (default 1.0), `pinch_height` (metres above the base frame, default 0.135).
///
/// Environments: `sim`; `mock` (moves at the requested speed, never meets an object); `real`:
/// the gripper through the Robotiq URCap's socket on its UR controller (interface settings
/// `host`, `port` 63352, `reply_seconds`, `activation_seconds`), activated at bind, its status
/// read every 20 ms, a fault ending the run with the gripper's error. At shutdown it keeps its
/// grip: releasing could drop what it holds.
#[derive(Debug, Clone)]
pub struct Robotiq2f85(ParallelGripper);

impl Deref for Robotiq2f85 {
    type Target = ParallelGripper;

    fn deref(&self) -> &ParallelGripper {
        &self.0
    }
}

impl Robotiq2f85 {
    /// Binds a 2F-85 model in `sim` given its parts' `names` (yarok's template,
    /// [`GripperNames::YAROK_2F85`], or another model's such as Menagerie's,
    /// [`GripperNames::MENAGERIE_2F85`]).
    ///
    /// # Errors
    ///
    /// [`BindError`] when a part is missing or an actuator is not a position servo.
    pub fn bind_sim(bind: &mut Bind<Sim>, names: &GripperNames) -> Result<Self, BindError> {
        ParallelGripper::bind_sim(bind, names).map(Self)
    }
}

impl Component for Robotiq2f85 {
    fn declaration() -> Declaration {
        Declaration::new("robotiq_2f85")
            .default("pad_friction", 1.0)
            .default("pinch_height", 0.135)
            .default("damping", DAMPING)
            .template(include_str!("robotiq_2f85.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces
            .add::<Sim>()
            .add::<Mock>()
            .add::<yarok_hw::Real>();
    }
}

impl Interface<Sim> for Robotiq2f85 {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Self::bind_sim(bind, &GripperNames::YAROK_2F85)
    }
}

impl Interface<Mock> for Robotiq2f85 {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Ok(Self(ParallelGripper::mock(bind, Stroke::ROBOTIQ_2F85)))
    }
}
