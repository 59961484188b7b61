//! [`ServoFingers`]: a simulated gripper's fingers, moved by the position servos of its model.

use std::cell::RefCell;

use yarok_core::component::{Bind, BindError};
use yarok_mjc::{Actuator, Body, ServoGains, Sim, SimBind, Site};

use super::drive::{FingerDrive, Request};
use super::names::{FingerServo, GripperNames, Stroke};
use super::ramp::Ramp;

/// Positions a second below which the fingers count as stopped (0.02 rad/s of the 2F-85's
/// 0.8 rad driver stroke).
const STOPPED_POSITIONS_PER_S: f64 = 6.375;

/// A simulated gripper's fingers: its servos, driven together to a position command that
/// moves toward each request at its speed, their squeeze capped by the request's force (10 %
/// to 100 % of the most each servo may give: its force range's top, or for a servo without
/// one, what it gives across the whole stroke).
#[derive(Debug)]
pub struct ServoFingers {
    servos: Vec<Servo>,
    stroke: Stroke,
    pads: [Body; 2],
    pad_sites: Option<[Site; 2]>,
    reached: f64,
    ramp: RefCell<Ramp>,
}

/// One position servo, in its length's units (a joint's or a tendon's, times its gear).
#[derive(Debug)]
struct Servo {
    actuator: Actuator,
    gains: ServoGains,
    /// Its controls at the open and closed ends.
    ends: [f64; 2],
    max_force: f64,
}

impl Servo {
    fn bind(bind: &Bind<Sim>, names: &FingerServo) -> Result<Self, BindError> {
        let actuator = bind.actuator(names.actuator)?;
        let gains = actuator
            .servo_gains()
            .filter(|gains| gains.kp > 0.0)
            .ok_or_else(|| {
                bind.error(format!(
                    "actuator {:?} is not a position servo (a fixed gain and an affine bias \
                     that pulls back, on a joint or tendon): the gripper drives one",
                    names.actuator
                ))
            })?;
        if names.open == names.closed {
            return Err(bind.error(format!(
                "actuator {:?}: its controls open ({}) and closed ({}) must differ",
                names.actuator, names.open, names.closed
            )));
        }
        let stroke_force = gains.gain * (names.closed - names.open).abs();
        let max_force = gains.force_range.map_or(stroke_force, |[_, most]| most);
        if !(max_force > 0.0 && max_force.is_finite()) {
            return Err(bind.error(format!(
                "actuator {:?} needs a force range whose top is above 0 (forcerange), the \
                 most the gripper may squeeze",
                names.actuator
            )));
        }
        Ok(Self {
            actuator,
            gains,
            ends: [names.open, names.closed],
            max_force,
        })
    }

    /// Where it is (positions, 0 open to 255 closed) and how fast it moves (positions a
    /// second).
    fn position(&self) -> (f64, f64) {
        let (length, rate) = self.actuator.length();
        let ServoGains { gain, kp, .. } = self.gains;
        let [open, closed] = self.ends.map(|control| gain * control / kp);
        let per_length = 255.0 / (closed - open);
        ((length - open) * per_length, rate * per_length)
    }

    /// Drives it toward `command` (0–255) squeezing at most with `force` (0–255); returns
    /// whether the squeeze was capped.
    fn drive(&self, command: f64, force: f64) -> bool {
        let ServoGains { gain, kp, kv, .. } = self.gains;
        let (length, rate) = self.actuator.length();
        let [open, closed] = self.ends;
        let target = open + (closed - open) * command / 255.0;
        // The cap: never more force than `squeeze` beyond holding where and as fast as it is.
        let squeeze = self.max_force * (0.1 + 0.9 * force / 255.0);
        let holding = kp * length + kv * rate;
        let lowest = ((holding - squeeze) / gain).max(open.min(closed));
        let highest = ((holding + squeeze) / gain).min(open.max(closed));
        let capped = target.min(highest).max(lowest);
        self.actuator.set(capped);
        capped != target
    }
}

impl ServoFingers {
    /// The fingers of the gripper `names` describes.
    ///
    /// # Errors
    ///
    /// [`BindError`] when a part is missing, an actuator is not a position servo or its
    /// controls at the ends are the same.
    pub fn bind(bind: &Bind<Sim>, names: &GripperNames) -> Result<Self, BindError> {
        if names.servos.is_empty() {
            return Err(bind.error("a gripper needs at least one servo"));
        }
        let servos = names
            .servos
            .iter()
            .map(|servo| Servo::bind(bind, servo))
            .collect::<Result<_, _>>()?;
        let pad_sites = match names.pad_sites {
            Some([left, right]) => Some([bind.site(left)?, bind.site(right)?]),
            None => None,
        };
        Ok(Self {
            servos,
            stroke: names.stroke,
            pads: [bind.body(names.pads[0])?, bind.body(names.pads[1])?],
            pad_sites,
            reached: names.reached,
            ramp: RefCell::new(Ramp::START),
        })
    }

    /// The servos' mean position and speed (positions, positions a second).
    fn position_and_speed(&self) -> (f64, f64) {
        let count = self.servos.len() as f64;
        let (position, speed) = self
            .servos
            .iter()
            .map(Servo::position)
            .fold((0.0, 0.0), |(p, s), (position, speed)| {
                (p + position, s + speed)
            });
        (position / count, speed / count)
    }
}

impl FingerDrive for ServoFingers {
    fn position(&self) -> f64 {
        self.position_and_speed().0
    }

    fn is_moving(&self) -> bool {
        self.ramp.borrow().is_running()
            || self
                .servos
                .iter()
                .any(|servo| servo.position().1.abs() > STOPPED_POSITIONS_PER_S)
    }

    fn requested(&self) -> Request {
        self.ramp.borrow().request
    }

    fn reach_tolerance(&self) -> f64 {
        self.reached
    }

    fn request(&self, request: Request) {
        // The ramp starts where the fingers are (they may be squeezing an object).
        let from = self.position();
        self.ramp.borrow_mut().start(request, from);
    }

    fn tick(&self, timestep: f64) {
        let mut ramp = self.ramp.borrow_mut();
        let command = ramp.advance(&self.stroke, timestep);
        let force = ramp.request.force;
        // Every servo is driven; the squeeze is capped when it is on all of them.
        let uncapped = self
            .servos
            .iter()
            .map(|servo| servo.drive(command, force))
            .filter(|capped| !capped)
            .count();
        let capped = uncapped == 0;
        let still = self.position_and_speed().1.abs() < STOPPED_POSITIONS_PER_S;
        ramp.note_blocked(capped && still);
    }

    fn restart(&self) {
        *self.ramp.borrow_mut() = Ramp::START;
    }

    fn pads(&self) -> Option<[Body; 2]> {
        Some(self.pads.clone())
    }

    fn pad_sites(&self) -> Option<[Site; 2]> {
        self.pad_sites.clone()
    }
}
