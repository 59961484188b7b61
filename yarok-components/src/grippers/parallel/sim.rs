//! [`ServoFingers`]: a simulated gripper's fingers, moved by the position servos of its model.

use std::cell::RefCell;

use yarok_core::component::{Bind, BindError};
use yarok_mjc::{Actuator, Body, ServoGains, Sim, SimBind, Site};

use super::drive::{FingerDrive, Request};
use super::names::{FingerServo, GripperNames, Stroke};
use super::ramp::Ramp;

/// How far (millimetres) a measured gripper's pads may stand off the opening its stroke has at
/// a request and not count as holding an object: the sinking of soft pads into what they
/// touch (1.5–1.9 mm measured on the 2F-85).
const OBJECT_MM: f64 = 2.5;

/// The share of its fastest speed below which a gripper's fingers count as stopped (0.02 rad/s
/// of the 2F-85's 0.8 rad driver stroke, at its 1.4 rad/s).
const STOPPED_SHARE: f64 = 0.014;

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
    /// Whether the stroke was measured: the opening is then the pads' gap, measured, and an
    /// object is found by it.
    measured: bool,
    ramp: RefCell<Ramp>,
}

/// One position servo, in its length's units (a joint's or a tendon's, times its gear).
#[derive(Debug)]
struct Servo {
    actuator: Actuator,
    gains: ServoGains,
    /// Its controls at the open and closed ends.
    ends: [f64; 2],
    /// Its lengths there: where the servo settles at those controls (measured), or, by
    /// default, where its gains put it.
    lengths: [f64; 2],
    max_force: f64,
}

impl Servo {
    fn bind(
        bind: &Bind<Sim>,
        names: &FingerServo,
        lengths: Option<[f64; 2]>,
    ) -> Result<Self, BindError> {
        let (actuator, gains) = position_servo(bind, names.actuator)?;
        if !(names.open.is_finite() && names.closed.is_finite()) || names.open == names.closed {
            return Err(bind.error(format!(
                "actuator {:?}: its controls open ({}) and closed ({}) must be two different \
                 numbers",
                names.actuator, names.open, names.closed
            )));
        }
        if let Some([lowest, highest]) = actuator.ctrl_range() {
            for (end, control) in [("open", names.open), ("closed", names.closed)] {
                if !(lowest..=highest).contains(&control) {
                    return Err(bind.error(format!(
                        "actuator {:?}: its control {end} ({control}) is outside its control \
                         range [{lowest}, {highest}]",
                        names.actuator
                    )));
                }
            }
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
        let ends = [names.open, names.closed];
        Ok(Self {
            actuator,
            lengths: lengths.unwrap_or(ends.map(|control| gains.gain * control / gains.kp)),
            gains,
            ends,
            max_force,
        })
    }

    /// Where it is (positions, 0 open to 255 closed) and how fast it moves (positions a
    /// second).
    fn position(&self) -> (f64, f64) {
        let (length, rate) = self.actuator.length();
        let [open, closed] = self.lengths;
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

/// The actuator `name` as a position servo, with its gains; an error saying what it is not.
pub(super) fn position_servo(
    bind: &Bind<Sim>,
    name: &str,
) -> Result<(Actuator, ServoGains), BindError> {
    let actuator = bind.actuator(name)?;
    let gains = actuator
        .servo_gains()
        .filter(|gains| gains.kp > 0.0)
        .ok_or_else(|| {
            bind.error(format!(
                "actuator {name:?} is not a position servo (a fixed gain and an affine bias \
                 that pulls back, on a joint or tendon): the gripper drives one"
            ))
        })?;
    Ok((actuator, gains))
}

/// Refuses a gripper of no servos, or whose two pads are one.
pub(super) fn check_servos_and_pads(
    bind: &Bind<Sim>,
    servos: usize,
    pads: [&str; 2],
) -> Result<(), BindError> {
    if servos == 0 {
        return Err(bind.error("a gripper needs at least one servo"));
    }
    if pads[0] == pads[1] {
        return Err(bind.error(format!(
            "the pads are both {:?}: a parallel gripper has a left and a right pad",
            pads[0]
        )));
    }
    Ok(())
}

impl ServoFingers {
    /// The fingers of the gripper `names` describes.
    ///
    /// # Errors
    ///
    /// [`BindError`] when a part is missing, an actuator is not a position servo or its
    /// controls at the ends are the same.
    pub fn bind(bind: &Bind<Sim>, names: &GripperNames) -> Result<Self, BindError> {
        Self::new(
            bind,
            names.servos,
            None,
            names.pads,
            names.pad_sites,
            names.stroke.clone(),
            names.reached,
        )
    }

    /// The fingers of a gripper closed by `servos` (each servo's lengths at its open and
    /// closed controls, when its stroke was measured: the opening is then measured between the
    /// pads, and an object found by it), with its pads' bodies (and the sites on their faces,
    /// if given), its stroke and reach tolerance (positions).
    pub(super) fn new(
        bind: &Bind<Sim>,
        servos: &[FingerServo],
        lengths: Option<&[[f64; 2]]>,
        pads: [&str; 2],
        pad_sites: Option<[&str; 2]>,
        stroke: Stroke,
        reached: f64,
    ) -> Result<Self, BindError> {
        check_servos_and_pads(bind, servos.len(), pads)?;
        if !(reached.is_finite() && reached > 0.0) {
            return Err(bind.error(format!(
                "reached {reached} must be a positive number of positions"
            )));
        }
        let servos = servos
            .iter()
            .enumerate()
            .map(|(i, servo)| Servo::bind(bind, servo, lengths.map(|lengths| lengths[i])))
            .collect::<Result<_, _>>()?;
        let pad_sites = match pad_sites {
            Some([left, right]) => Some([bind.site(left)?, bind.site(right)?]),
            None => None,
        };
        Ok(Self {
            servos,
            stroke,
            pads: [bind.body(pads[0])?, bind.body(pads[1])?],
            pad_sites,
            reached,
            measured: lengths.is_some(),
            ramp: RefCell::new(Ramp::START),
        })
    }

    /// The gap between the pads' surfaces (millimetres, 0 where they touch).
    fn gap_mm(&self) -> f64 {
        self.pads[0]
            .gap_to(&self.pads[1])
            .map_or(0.0, |gap| gap.max(0.0) * 1e3)
    }

    /// Positions a second below which the fingers count as stopped.
    fn stopped(&self) -> f64 {
        STOPPED_SHARE * self.stroke.positions_per_second(255.0)
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
                .any(|servo| servo.position().1.abs() > self.stopped())
    }

    fn requested(&self) -> Request {
        self.ramp.borrow().request
    }

    fn reach_tolerance(&self) -> f64 {
        self.reached
    }

    fn opening_mm(&self, stroke: &Stroke) -> f64 {
        if self.measured {
            self.gap_mm()
        } else {
            stroke.opening_at(self.position())
        }
    }

    fn object_detected(&self) -> bool {
        if self.is_moving() {
            return false;
        }
        let request = self.requested().position;
        if !self.measured {
            return (self.position().round() - request).abs() > self.reached;
        }
        // The pads stand wider than the sweep saw them at the request, by more than the
        // servos' reach tolerance and the pads' sinking into what they hold allow (an object
        // between them; closing narrower than the sweep is the servos squeezing harder).
        let stroke = &self.stroke;
        let per_position =
            (stroke.opening_at(request - 1.0) - stroke.opening_at(request + 1.0)).abs() / 2.0;
        let tolerance = (per_position * self.reached).max(OBJECT_MM);
        self.gap_mm() - stroke.opening_at(request) > tolerance
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
        let still = self.position_and_speed().1.abs() < self.stopped();
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
