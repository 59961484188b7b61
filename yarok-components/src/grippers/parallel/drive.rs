//! [`FingerDrive`]: how a parallel gripper's fingers are moved in one environment.

use yarok_mjc::{Body, Site};

use super::names::Stroke;

/// A gripper request: position (0 open to 255 closed), speed and force, each 0–255.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Request {
    /// Where the fingers are to go, 0 (open) to 255 (closed).
    pub position: f64,
    /// The least (0) to the most (255) speed.
    pub speed: f64,
    /// The least (0) to the most (255) squeeze.
    pub force: f64,
}

impl Request {
    /// Open, at full speed and half force, as a gripper is at power-on.
    pub const POWER_ON: Self = Self {
        position: 0.0,
        speed: 255.0,
        force: 128.0,
    };
}

/// The fingers of a [`ParallelGripper`](super::ParallelGripper) in one environment: the
/// simulated servos, a mock, a real gripper's driver, or a user's own (a replay, another
/// simulator). The gripper's handle holds one and calls nothing else.
pub trait FingerDrive {
    /// Where the fingers are, 0.0 (open) to 255.0 (closed).
    fn position(&self) -> f64;

    /// Whether the fingers are moving, or the latest request is still under way.
    fn is_moving(&self) -> bool;

    /// The latest request (as [`FingerDrive::request`] was given it).
    fn requested(&self) -> Request;

    /// Starts a request; it replaces the one under way.
    fn request(&self, request: Request);

    /// How many positions short of a request the fingers may stop and count as there:
    /// [`REACHED_COUNTS`](super::REACHED_COUNTS) unless the fingers' friction needs more.
    fn reach_tolerance(&self) -> f64 {
        super::REACHED_COUNTS
    }

    /// Whether the fingers stopped on an object before reaching the request. By default:
    /// stopped more than [`FingerDrive::reach_tolerance`] positions short of it.
    fn object_detected(&self) -> bool {
        !self.is_moving()
            && (self.position().round() - self.requested().position).abs() > self.reach_tolerance()
    }

    /// The opening between the pad faces (millimetres) over `stroke`. By default read from the
    /// stroke's table at [`FingerDrive::position`]; a simulation may measure it.
    fn opening_mm(&self, stroke: &Stroke) -> f64 {
        stroke.opening_at(self.position())
    }

    /// Runs after each step of the platform, `timestep` seconds long.
    fn tick(&self, timestep: f64) {
        let _ = timestep;
    }

    /// The run restarts from its start state.
    fn restart(&self) {}

    /// The pads' bodies `[left, right]`, where there is a simulation.
    fn pads(&self) -> Option<[Body; 2]> {
        None
    }

    /// The sites on the pads' faces, where there is a simulation and the model has them.
    fn pad_sites(&self) -> Option<[Site; 2]> {
        None
    }
}
