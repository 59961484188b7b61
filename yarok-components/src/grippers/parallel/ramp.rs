//! [`Ramp`]: a request's command, moving toward it at the requested speed.

use super::drive::Request;
use super::names::Stroke;

/// Ticks the fingers must stand still at their force cap to count as blocked.
const STALLED_TICKS: u32 = 10;

/// The request under way and the position command moving toward it, as the real gripper's
/// controller moves its own.
#[derive(Debug, Clone, Copy)]
pub(super) struct Ramp {
    /// The request.
    pub(super) request: Request,
    /// The position command (0–255), moving to the request at its speed.
    pub(super) command: f64,
    /// Ticks the request has run.
    ticks: u64,
    /// Ticks the fingers have stood still with their squeeze capped.
    stalled: u32,
}

impl Ramp {
    /// Open, as at power-on.
    pub(super) const START: Self = Self {
        request: Request::POWER_ON,
        command: 0.0,
        ticks: 2,
        stalled: 0,
    };

    /// Starts `request` with the command at `from`.
    pub(super) fn start(&mut self, request: Request, from: f64) {
        *self = Self {
            request,
            command: from.clamp(0.0, 255.0),
            ticks: 0,
            stalled: 0,
        };
    }

    /// Moves the command one tick of `timestep` seconds toward the request; returns it.
    pub(super) fn advance(&mut self, stroke: &Stroke, timestep: f64) -> f64 {
        let step = stroke.positions_per_second(self.request.speed) * timestep;
        self.command += (self.request.position - self.command).clamp(-step, step);
        self.ticks += 1;
        self.command
    }

    /// Counts a tick on which the fingers stood still with their squeeze capped (`blocked`);
    /// after [`STALLED_TICKS`] of them the request is as far as the fingers go.
    pub(super) fn note_blocked(&mut self, blocked: bool) {
        self.stalled = if blocked { self.stalled + 1 } else { 0 };
        if self.stalled >= STALLED_TICKS {
            self.command = self.request.position;
        }
    }

    /// Whether the command is still moving toward the request (or the request is new).
    pub(super) fn is_running(&self) -> bool {
        self.command != self.request.position || self.ticks < 2
    }
}
