//! How the fake controller's arm moves: [`ArmMotion`], the commands its scripts give, and
//! [`Interpolated`], a stand-in for protocol tests whose joints move linearly in time. The
//! workspace's tests plug in the project's simulated UR model instead
//! (`tests/support/simulated_ur.rs`).

use std::time::Instant;

/// What a script asks of the arm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArmCommand {
    /// `movej`: to joints `to`, the leading joint at `speed` rad/s and `acceleration` rad/s².
    #[allow(missing_docs)]
    Joints {
        to: [f64; 6],
        speed: f64,
        acceleration: f64,
    },
    /// `movel`: the TCP `tcp` (a pose vector in the flange frame, as `set_tcp` set it) along a
    /// line to `pose` (a pose vector in the base frame), at `speed` m/s and `acceleration` m/s².
    #[allow(missing_docs)]
    Line {
        pose: [f64; 6],
        tcp: [f64; 6],
        speed: f64,
        acceleration: f64,
    },
    /// `servoj`: the joints held at `to`, reached within `seconds` (the client's control
    /// period); a motion under way ends.
    #[allow(missing_docs)]
    Servo { to: [f64; 6], seconds: f64 },
    /// `stopj`/`stopl`, or a protective stop: the motion under way ends.
    Stop,
}

/// The arm as its controller reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmState {
    /// Joint angles (radians).
    pub q: [f64; 6],
    /// Joint speeds (rad/s).
    pub qd: [f64; 6],
    /// The joints the motion under way ends at (`q` at rest).
    pub target: [f64; 6],
    /// Whether a motion is under way.
    pub moving: bool,
}

/// The arm behind the fake controller's interfaces.
pub trait ArmMotion: Send {
    /// Where the arm is now.
    fn state(&self) -> ArmState;
    /// Runs a command from a script.
    fn command(&mut self, command: ArmCommand);
    /// Puts the arm at rest at `q`, as a test's setup does.
    fn place(&mut self, q: [f64; 6]);
}

/// Joints at rest or moving linearly from one position to another at the speed asked for;
/// `movel` is kept unanswered (no kinematics here); a stop is instant.
#[derive(Debug, Clone)]
pub struct Interpolated {
    from: [f64; 6],
    to: [f64; 6],
    started: Instant,
    seconds: f64,
}

impl Interpolated {
    /// Standing at `q`.
    pub fn at(q: [f64; 6]) -> Self {
        Self {
            from: q,
            to: q,
            started: Instant::now(),
            seconds: 0.0,
        }
    }

    fn fraction(&self, now: Instant) -> f64 {
        if self.seconds > 0.0 {
            (now.duration_since(self.started).as_secs_f64() / self.seconds).min(1.0)
        } else {
            1.0
        }
    }

    fn q(&self, now: Instant) -> [f64; 6] {
        let fraction = self.fraction(now);
        std::array::from_fn(|i| self.from[i] + (self.to[i] - self.from[i]) * fraction)
    }
}

impl ArmMotion for Interpolated {
    fn state(&self) -> ArmState {
        let now = Instant::now();
        let moving = self.fraction(now) < 1.0;
        ArmState {
            q: self.q(now),
            qd: std::array::from_fn(|i| {
                if moving {
                    (self.to[i] - self.from[i]) / self.seconds
                } else {
                    0.0
                }
            }),
            target: self.to,
            moving,
        }
    }

    fn command(&mut self, command: ArmCommand) {
        let now = Instant::now();
        match command {
            ArmCommand::Joints { to, speed, .. } => {
                let from = self.q(now);
                let farthest = (0..6).map(|i| (to[i] - from[i]).abs()).fold(0.0, f64::max);
                *self = Self {
                    from,
                    to,
                    started: now,
                    seconds: farthest / speed.max(1e-3),
                };
            }
            ArmCommand::Servo { to, seconds } => {
                *self = Self {
                    from: self.q(now),
                    to,
                    started: now,
                    seconds: seconds.max(0.0),
                };
            }
            ArmCommand::Line { .. } => {}
            ArmCommand::Stop => *self = Self::at(self.q(now)),
        }
    }

    fn place(&mut self, q: [f64; 6]) {
        *self = Self::at(q);
    }
}
