//! [`Robotiq2f85`]: the Robotiq 2F-85 adaptive gripper, with the real gripper's requests and
//! status — position, speed and force 0–255, and `gOBJ`'s object detection.

use std::cell::RefCell;
use std::future::{Future, IntoFuture};
use std::pin::Pin;
use std::rc::Rc;

use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces, Mock};
use yarok_core::time::{Clock, WaitError};
use yarok_mjc::{Actuator, Body, Joint, ServoGains, Sim, SimBind, Site};

mod real;

use real::RealFingers;

/// The driver angle (radians) at which the fingers close on nothing; position 255.
const CLOSED_RAD: f64 = 0.8;

/// The damping (tendon units) of the bundled template's servo unless configured.
const DAMPING: f64 = 2.0;

/// The gap between the pad faces (millimetres) at driver angles 0, 0.2, 0.4, 0.6 and 0.8 rad.
const GAP_MM: [f64; 5] = [85.4, 66.6, 45.6, 23.1, 0.2];

/// Positions (counts) within which a request counts as reached ([`Robotiq2f85::object_detected`]
/// is false).
pub const REACHED_COUNTS: f64 = 3.0;

/// Ticks the fingers must stand still at their force cap to count as blocked.
const STALLED_TICKS: u32 = 10;

/// Driver speed (rad/s) below which the fingers count as stopped.
const STOPPED_RAD_S: f64 = 0.02;

/// A Robotiq 2F-85 gripper: 85 mm stroke, position requests 0 (open) to 255 (closed) at a
/// speed and force 0–255 (20–150 mm/s; the least to the most squeeze), and the real gripper's
/// status: position, motion, and whether it stopped on an object before its request (`gOBJ`).
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
#[derive(Clone)]
pub struct Robotiq2f85 {
    inner: Rc<Inner>,
}

struct Inner {
    clock: Clock,
    drive: Drive,
    state: RefCell<State>,
}

enum Drive {
    Sim(Box<Fingers>),
    Mock,
    Real(Rc<RealFingers>),
}

/// The simulated gripper's actuator (a position servo on the drivers' tendon, command 0–255),
/// its gains and force cap as the model states them, drivers and pads.
struct Fingers {
    actuator: Actuator,
    gains: ServoGains,
    max_force: f64,
    drivers: [Joint; 2],
    pads: [Body; 2],
    pad_sites: Option<[Site; 2]>,
}

/// The names of a 2F-85 model's parts: its actuator, the two driver joints and the pads'
/// bodies `[left, right]`, and the sites on the pads' faces if it has them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GripperNames {
    /// The position servo on the drivers (command 0–255).
    pub actuator: &'static str,
    /// The driver joints.
    pub drivers: [&'static str; 2],
    /// The pads' bodies.
    pub pads: [&'static str; 2],
    /// Sites on the pads' faces.
    pub pad_sites: Option<[&'static str; 2]>,
}

impl GripperNames {
    /// The names in yarok's own template ([`Robotiq2f85`]).
    pub const YAROK: Self = Self {
        actuator: "fingers",
        drivers: ["left_driver", "right_driver"],
        pads: ["left_pad", "right_pad"],
        pad_sites: Some(["left_pad", "right_pad"]),
    };

    /// The names in MuJoCo Menagerie's `robotiq_2f85/2f85.xml`.
    pub const MENAGERIE: Self = Self {
        actuator: "fingers_actuator",
        drivers: ["left_driver_joint", "right_driver_joint"],
        pads: ["left_pad", "right_pad"],
        pad_sites: None,
    };
}

#[derive(Debug, Clone, Copy)]
struct State {
    /// The request: position, speed and force, 0–255.
    request: [f64; 3],
    /// The position command (counts), ramping to the request at its speed.
    command: f64,
    /// Ticks the current request has run.
    ticks: u64,
    /// Ticks the fingers have stood still with the squeeze capped: blocked by an object.
    stalled: u32,
}

impl State {
    /// Open, at full speed and half force, as at power-on.
    const START: Self = Self {
        request: [0.0, 255.0, 128.0],
        command: 0.0,
        ticks: 2,
        stalled: 0,
    };
}

impl std::fmt::Debug for Robotiq2f85 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Robotiq2f85")
            .field("position", &self.position())
            .finish()
    }
}

impl Robotiq2f85 {
    /// A request for `position` (0 open to 255 closed) at full speed and half force; set them
    /// with [`Grip::speed`] and [`Grip::force`], then `.await` it or [`Grip::start`] it.
    pub fn move_to(&self, position: u8) -> Grip<'_> {
        Grip {
            gripper: self,
            request: [f64::from(position), 255.0, 128.0],
        }
    }

    /// [`Robotiq2f85::move_to`] an opening of `millimetres` between the pads (0 to 85.4).
    pub fn move_to_mm(&self, millimetres: f64) -> Grip<'_> {
        self.move_to(counts_for_gap(millimetres))
    }

    /// Opens fully.
    pub fn open(&self) -> Grip<'_> {
        self.move_to(0)
    }

    /// Closes fully (until the pads meet, or meet an object).
    pub fn close(&self) -> Grip<'_> {
        self.move_to(255)
    }

    /// Where the fingers are, 0 (open) to 255 (closed).
    pub fn position(&self) -> u8 {
        (self.inner.driver_angle() / CLOSED_RAD * 255.0)
            .round()
            .clamp(0.0, 255.0) as u8
    }

    /// The opening between the pad faces in millimetres.
    pub fn opening_mm(&self) -> f64 {
        gap_for_angle(self.inner.driver_angle())
    }

    /// Whether the fingers are moving (or their command is still ramping to the request).
    pub fn is_moving(&self) -> bool {
        self.inner.is_moving()
    }

    /// Whether the fingers stopped before reaching the request: an object is held (the real
    /// gripper's `gOBJ` 1 or 2).
    pub fn object_detected(&self) -> bool {
        if let Drive::Real(fingers) = &self.inner.drive {
            return fingers.object_detected();
        }
        let request = self.inner.state.borrow().request[0];
        !self.is_moving() && (f64::from(self.position()) - request).abs() > REACHED_COUNTS
    }

    /// The pads' bodies `[left, right]` (sim only; `None` in mock and real).
    pub fn pads(&self) -> Option<[Body; 2]> {
        match &self.inner.drive {
            Drive::Sim(fingers) => Some(fingers.pads.clone()),
            Drive::Mock | Drive::Real(_) => None,
        }
    }

    /// The pad-face sites `[left, right]` (sim only, when the model has them).
    pub fn pad_sites(&self) -> Option<[Site; 2]> {
        match &self.inner.drive {
            Drive::Sim(fingers) => fingers.pad_sites.clone(),
            Drive::Mock | Drive::Real(_) => None,
        }
    }
}

impl Inner {
    fn driver_angle(&self) -> f64 {
        match &self.drive {
            Drive::Sim(fingers) => {
                0.5 * (fingers.drivers[0].position() + fingers.drivers[1].position())
            }
            Drive::Mock => self.state.borrow().command / 255.0 * CLOSED_RAD,
            Drive::Real(fingers) => f64::from(fingers.position()) / 255.0 * CLOSED_RAD,
        }
    }

    fn driver_speed(&self) -> f64 {
        match &self.drive {
            Drive::Sim(fingers) => {
                0.5 * (fingers.drivers[0].velocity() + fingers.drivers[1].velocity())
            }
            Drive::Mock | Drive::Real(_) => 0.0,
        }
    }

    fn is_moving(&self) -> bool {
        if let Drive::Real(fingers) = &self.drive {
            return fingers.is_moving();
        }
        let state = *self.state.borrow();
        if state.command != state.request[0] || state.ticks < 2 {
            return true;
        }
        match &self.drive {
            Drive::Sim(fingers) => fingers
                .drivers
                .iter()
                .any(|driver| driver.velocity().abs() > STOPPED_RAD_S),
            Drive::Mock | Drive::Real(_) => false,
        }
    }

    /// After a step: ramps the command toward the request at its speed, with its force.
    fn tick(&self) {
        let mut state = self.state.borrow_mut();
        let [position, speed, force] = state.request;
        // 20 to 150 mm/s of opening; 255 counts span the 85 mm stroke.
        let counts_per_second = (20.0 + 130.0 * speed / 255.0) * 255.0 / 85.0;
        let step = counts_per_second * self.clock.timestep();
        state.command += (position - state.command).clamp(-step, step);
        state.ticks += 1;
        let command = state.command;
        drop(state);
        if let Drive::Sim(fingers) = &self.drive {
            // The force request caps the squeeze: the command never asks more than it of the
            // actuator beyond holding the drivers where and as fast as they are.
            let ServoGains { gain, kp, kv, .. } = fingers.gains;
            let squeeze = fingers.max_force * (0.1 + 0.9 * force / 255.0);
            let holding = kp * self.driver_angle() + kv * self.driver_speed();
            let held = (holding + squeeze) / gain;
            let released = (holding - squeeze) / gain;
            let target = command / 255.0 * CLOSED_RAD * kp / gain;
            let capped = target.clamp(released.max(0.0), held.min(255.0));
            fingers.actuator.set(capped);
            let mut state = self.state.borrow_mut();
            if capped != target && self.driver_speed().abs() < STOPPED_RAD_S {
                state.stalled += 1;
            } else {
                state.stalled = 0;
            }
            if state.stalled >= STALLED_TICKS {
                // Blocked: the request is as far as the fingers go.
                state.command = state.request[0];
            }
        }
    }
}

/// The gripper request 0–255 for an opening of `millimetres`, by the linkage's table.
fn counts_for_gap(millimetres: f64) -> u8 {
    let gap = millimetres.clamp(GAP_MM[4], GAP_MM[0]);
    let segment = GAP_MM.windows(2).position(|w| gap >= w[1]).unwrap_or(3);
    let (wide, narrow) = (GAP_MM[segment], GAP_MM[segment + 1]);
    let angle = 0.2 * (segment as f64 + (wide - gap) / (wide - narrow));
    (angle / CLOSED_RAD * 255.0).round().clamp(0.0, 255.0) as u8
}

/// The opening (millimetres) at a driver angle, by the linkage's table.
fn gap_for_angle(angle: f64) -> f64 {
    let position = (angle / 0.2).clamp(0.0, 4.0);
    let segment = (position.floor() as usize).min(3);
    let fraction = position - segment as f64;
    GAP_MM[segment] + (GAP_MM[segment + 1] - GAP_MM[segment]) * fraction
}

/// How a gripper request ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gripped {
    /// Where the fingers stopped, 0–255.
    pub position: u8,
    /// Whether they stopped on an object before the request.
    pub object_detected: bool,
}

/// A gripper request about to start: `.await` it (it resolves once the fingers stop) or
/// [`Grip::start`] it.
///
/// # Cancel safety
///
/// Dropping the awaited future leaves the request running, as on the real gripper.
#[must_use = "a gripper request does nothing until awaited or started"]
#[derive(Debug)]
pub struct Grip<'a> {
    gripper: &'a Robotiq2f85,
    request: [f64; 3],
}

impl Grip<'_> {
    /// Speed request 0–255 (20 to 150 mm/s).
    pub fn speed(mut self, speed: u8) -> Self {
        self.request[1] = f64::from(speed);
        self
    }

    /// Force request 0–255 (the least to the most squeeze).
    pub fn force(mut self, force: u8) -> Self {
        self.request[2] = f64::from(force);
        self
    }

    /// Sends the request and returns at once.
    pub fn start(self) {
        let inner = &self.gripper.inner;
        // The ramp starts where the fingers are (they may be squeezing an object).
        let at = inner.driver_angle() / CLOSED_RAD * 255.0;
        let mut state = inner.state.borrow_mut();
        if matches!(inner.drive, Drive::Sim(_)) {
            state.command = at.clamp(0.0, 255.0);
        }
        state.request = self.request;
        state.ticks = 0;
        state.stalled = 0;
        if let Drive::Real(fingers) = &inner.drive {
            fingers.request(self.request.map(|value| value.clamp(0.0, 255.0) as u8));
        }
    }
}

impl<'a> IntoFuture for Grip<'a> {
    type Output = Result<Gripped, WaitError>;
    type IntoFuture = Pin<Box<dyn Future<Output = Self::Output> + 'a>>;

    fn into_future(self) -> Self::IntoFuture {
        let gripper = self.gripper;
        let speed = self.request[1];
        self.start();
        Box::pin(async move {
            // The slowest full stroke takes 85 mm / 20 mm/s; a second more to settle.
            let bound = 85.0 / (20.0 + 130.0 * speed / 255.0) + 1.0;
            gripper
                .inner
                .clock
                .wait(|| !gripper.is_moving())
                .timeout(bound)
                .await?;
            Ok(Gripped {
                position: gripper.position(),
                object_detected: gripper.object_detected(),
            })
        })
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

impl Robotiq2f85 {
    fn with_drive<E: yarok_core::component::Environment>(bind: &mut Bind<E>, drive: Drive) -> Self {
        let simulated = matches!(drive, Drive::Sim(_));
        let gripper = Self {
            inner: Rc::new(Inner {
                clock: bind.clock(),
                drive,
                state: RefCell::new(State::START),
            }),
        };
        if simulated {
            let restarting = Rc::clone(&gripper.inner);
            bind.on_restart(move || *restarting.state.borrow_mut() = State::START);
        }
        let ticking = Rc::clone(&gripper.inner);
        bind.on_tick(move || {
            ticking.tick();
            Ok(())
        });
        gripper
    }
}

impl Robotiq2f85 {
    /// Binds a 2F-85 model in `sim` given its parts' `names` (yarok's template, or another
    /// model's such as Menagerie's): its actuator must be a position servo on the drivers whose
    /// command 0–255 closes them from 0 to 0.8 rad, as both models' are; its gains and force
    /// range are read from the model.
    ///
    /// # Errors
    ///
    /// [`BindError`] when a part is missing or the actuator is not such a servo.
    pub fn bind_sim(bind: &mut Bind<Sim>, names: GripperNames) -> Result<Self, BindError> {
        let actuator = bind.actuator(names.actuator)?;
        let gains = actuator.servo_gains().ok_or_else(|| {
            bind.error(format!(
                "actuator {:?} is not a position servo (a fixed gain and an affine bias on a \
                 joint or tendon): the gripper drives one",
                names.actuator
            ))
        })?;
        let max_force = gains.force_range.map_or(f64::INFINITY, |[_, most]| most);
        if !(max_force > 0.0 && max_force.is_finite()) {
            return Err(bind.error(format!(
                "actuator {:?} needs a force range whose top is above 0 (forcerange), the \
                 most the gripper may squeeze",
                names.actuator
            )));
        }
        let pad_sites = match names.pad_sites {
            Some([left, right]) => Some([bind.site(left)?, bind.site(right)?]),
            None => None,
        };
        let fingers = Fingers {
            actuator,
            gains,
            max_force,
            drivers: [bind.joint(names.drivers[0])?, bind.joint(names.drivers[1])?],
            pads: [bind.body(names.pads[0])?, bind.body(names.pads[1])?],
            pad_sites,
        };
        Ok(Self::with_drive(bind, Drive::Sim(Box::new(fingers))))
    }
}

impl Interface<Sim> for Robotiq2f85 {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Self::bind_sim(bind, GripperNames::YAROK)
    }
}

impl Interface<Mock> for Robotiq2f85 {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Ok(Self::with_drive(bind, Drive::Mock))
    }
}

#[cfg(test)]
mod tests {
    use super::{counts_for_gap, gap_for_angle};

    #[test]
    fn openings_and_requests_follow_the_linkage_table() {
        assert_eq!(counts_for_gap(85.4), 0);
        assert_eq!(counts_for_gap(0.2), 255);
        assert_eq!(counts_for_gap(45.6), 128);
        assert_eq!(counts_for_gap(1000.0), 0);
        assert!((gap_for_angle(0.4) - 45.6).abs() < 1e-9);
        assert!((gap_for_angle(0.1) - 76.0).abs() < 1e-9);
    }
}
