//! [`ParallelGripper`]: any two-finger gripper, driven as the Robotiq 2F-85 is — position,
//! speed and force 0–255, the opening in millimetres, and whether the fingers stopped on an
//! object.

use std::future::{Future, IntoFuture};
use std::pin::Pin;
use std::rc::Rc;

use yarok_core::component::{Bind, BindError, Environment};
use yarok_core::time::{Clock, WaitError};
use yarok_mjc::{Body, Sim, Site};

mod drive;
mod exposed;
mod measure;
mod mock;
mod names;
mod ramp;
mod sim;

pub use drive::{FingerDrive, Request};
pub use measure::GripperParts;
pub use mock::MockFingers;
pub use names::{FingerServo, GripperNames, Stroke};
pub use sim::ServoFingers;

/// Positions (counts) within which a request counts as reached
/// ([`ParallelGripper::object_detected`] is false).
pub const REACHED_COUNTS: f64 = 3.0;

/// A two-finger gripper: position requests 0 (open) to 255 (closed) at a speed and force
/// 0–255, its opening in millimetres by its [`Stroke`], and the real 2F-85's status: position,
/// motion, and whether the fingers stopped on an object before the request (`gOBJ`).
///
/// It holds a [`FingerDrive`] — the fingers in one environment — and works the same over any:
/// [`ParallelGripper::bind_sim`] drives any MJCF gripper's position servos given its
/// [`GripperNames`] (yarok's 2F-85, MuJoCo Menagerie's, robosuite's Franka hand),
/// [`MockFingers`] follow each request, and [`ParallelGripper::with_drive`] takes a drive of
/// your own.
///
/// # Examples
///
/// robosuite's Franka hand, wrapped unmodified:
///
/// ```no_run
/// use yarok_components::grippers::{GripperNames, ParallelGripper};
/// use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces};
/// use yarok_mjc::Sim;
///
/// struct FrankaHand(ParallelGripper);
///
/// impl Component for FrankaHand {
///     fn declaration() -> Declaration {
///         Declaration::new("franka_hand").mjcf_file("robosuite/models/assets/grippers/panda_gripper.xml")
///     }
///
///     fn interfaces(interfaces: &mut Interfaces<Self>) {
///         interfaces.add::<Sim>();
///     }
/// }
///
/// impl Interface<Sim> for FrankaHand {
///     async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
///         ParallelGripper::bind_sim(bind, &GripperNames::ROBOSUITE_PANDA).map(FrankaHand)
///     }
/// }
///
/// async fn grasp(hand: &FrankaHand) -> Result<bool, yarok_core::time::WaitError> {
///     hand.0.move_to_mm(79.0).await?;
///     Ok(hand.0.close().force(200).await?.object_detected)
/// }
/// ```
#[derive(Clone)]
pub struct ParallelGripper {
    drive: Rc<dyn FingerDrive>,
    stroke: Stroke,
    clock: Clock,
}

impl std::fmt::Debug for ParallelGripper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ParallelGripper")
            .field("position", &self.position())
            .finish()
    }
}

impl ParallelGripper {
    /// A gripper over `drive`, its opening given by `stroke`: the drive ticks after each step
    /// of the platform and restarts with the run. It publishes its `state` (`position`,
    /// `moving`, `object_detected`) and takes `command`s (`{"move_to": 0–255, "speed": …,
    /// "force": …}`, `{"open": true}`, `{"close": true}`) for any plugin.
    pub fn with_drive<E: Environment>(
        bind: &mut Bind<E>,
        drive: Rc<dyn FingerDrive>,
        stroke: Stroke,
    ) -> Self {
        let clock = bind.clock();
        let restarting = Rc::clone(&drive);
        bind.on_restart(move || restarting.restart());
        let ticking = Rc::clone(&drive);
        let ticks = clock.clone();
        bind.on_tick(move || {
            ticking.tick(ticks.timestep());
            Ok(())
        });
        let gripper = Self {
            drive,
            stroke,
            clock,
        };
        exposed::expose(bind, &gripper);
        gripper
    }

    /// A gripper with no physics behind it ([`MockFingers`]), moving over `stroke`.
    pub fn mock<E: Environment>(bind: &mut Bind<E>, stroke: Stroke) -> Self {
        Self::with_drive(bind, Rc::new(MockFingers::new(stroke.clone())), stroke)
    }

    /// Binds a gripper model in `sim` given its parts' `names`: each servo's gains, force
    /// range and controls are read from the model.
    ///
    /// # Errors
    ///
    /// [`BindError`] when a part is missing (naming the nearest the model has) or an actuator
    /// is not a position servo.
    pub fn bind_sim(bind: &mut Bind<Sim>, names: &GripperNames) -> Result<Self, BindError> {
        let fingers = ServoFingers::bind(bind, names)?;
        Ok(Self::with_drive(
            bind,
            Rc::new(fingers),
            names.stroke.clone(),
        ))
    }

    /// Binds a gripper model in `sim` named by its servos and pads alone ([`GripperParts`]):
    /// yarok measures the rest, sweeping the stroke in a copy of the model where only the
    /// gripper's own parts collide and the rest of the world holds still (once per model) —
    /// each servo's controls fully open and where the pads meet (or the fingers stop closing),
    /// the opening between the pads' surfaces over the stroke, how fast the fingers move, and
    /// how close the servos come to a request (the reach tolerance their friction needs).
    ///
    /// # Errors
    ///
    /// [`BindError`] when a part is missing, an actuator is not a position servo with a
    /// control range, a pad has no colliding geom, the gripper has an actuator the mapping
    /// leaves out (a hand of more than two fingers), or a servo moves neither pad (naming the
    /// likely cause: a third finger, or a file in radians read as degrees).
    pub fn bind_sim_measured(
        bind: &mut Bind<Sim>,
        parts: &GripperParts,
    ) -> Result<Self, BindError> {
        let measured = measure::measure(bind, parts)?;
        tracing::info!(
            "{}: measured the stroke, {:.1} to {:.1} mm between the pads, up to {:.0} mm/s, \
             requests reached within {:.1} positions",
            bind.path(),
            measured.stroke.opening_mm[0],
            measured.stroke.opening_mm[measured.stroke.opening_mm.len() - 1],
            measured.stroke.speed_mm_s[1],
            measured.reached
        );
        let fingers = ServoFingers::new(
            bind,
            &measured.servos,
            Some(&measured.lengths),
            parts.pads,
            parts.pad_sites,
            measured.stroke.clone(),
            measured.reached,
        )?;
        Ok(Self::with_drive(bind, Rc::new(fingers), measured.stroke))
    }

    /// A request for `position` (0 open to 255 closed) at full speed and half force; set them
    /// with [`Grip::speed`] and [`Grip::force`], then `.await` it or [`Grip::start`] it.
    pub fn move_to(&self, position: u8) -> Grip<'_> {
        Grip {
            gripper: self,
            request: Request {
                position: f64::from(position),
                ..Request::POWER_ON
            },
        }
    }

    /// [`ParallelGripper::move_to`] an opening of `millimetres` between the pads (within the
    /// stroke).
    pub fn move_to_mm(&self, millimetres: f64) -> Grip<'_> {
        self.move_to(self.stroke.position_for(millimetres))
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
        self.drive.position().round().clamp(0.0, 255.0) as u8
    }

    /// The opening between the pad faces in millimetres: measured between the pads' surfaces
    /// for a gripper yarok measured ([`ParallelGripper::bind_sim_measured`]), else read from
    /// the stroke's table at the fingers' position.
    pub fn opening_mm(&self) -> f64 {
        self.drive.opening_mm(&self.stroke)
    }

    /// The gripper's stroke: its openings and speeds.
    pub fn stroke(&self) -> &Stroke {
        &self.stroke
    }

    /// Whether the fingers are moving (or the request is still under way).
    pub fn is_moving(&self) -> bool {
        self.drive.is_moving()
    }

    /// Whether the fingers stopped before reaching the request: an object is held (the real
    /// gripper's `gOBJ` 1 or 2).
    pub fn object_detected(&self) -> bool {
        self.drive.object_detected()
    }

    /// The pads' bodies `[left, right]` (where there is a simulation).
    pub fn pads(&self) -> Option<[Body; 2]> {
        self.drive.pads()
    }

    /// The pad-face sites `[left, right]` (where there is a simulation and the model has them).
    pub fn pad_sites(&self) -> Option<[Site; 2]> {
        self.drive.pad_sites()
    }
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
    gripper: &'a ParallelGripper,
    request: Request,
}

impl Grip<'_> {
    /// Speed request 0–255 (the stroke's slowest to fastest).
    pub fn speed(mut self, speed: u8) -> Self {
        self.request.speed = f64::from(speed);
        self
    }

    /// Force request 0–255 (the least to the most squeeze).
    pub fn force(mut self, force: u8) -> Self {
        self.request.force = f64::from(force);
        self
    }

    /// Sends the request and returns at once.
    pub fn start(self) {
        self.gripper.drive.request(self.request);
    }
}

impl<'a> IntoFuture for Grip<'a> {
    type Output = Result<Gripped, WaitError>;
    type IntoFuture = Pin<Box<dyn Future<Output = Self::Output> + 'a>>;

    /// A request that times out is reported at the `.await` that made it.
    #[track_caller]
    fn into_future(self) -> Self::IntoFuture {
        let gripper = self.gripper;
        // The whole stroke at the requested speed, and a second more to settle.
        let bound = 255.0 / gripper.stroke.positions_per_second(self.request.speed) + 1.0;
        let stopped = gripper.clock.wait(|| !gripper.is_moving()).timeout(bound);
        self.start();
        Box::pin(async move {
            stopped.await?;
            Ok(Gripped {
                position: gripper.position(),
                object_detected: gripper.object_detected(),
            })
        })
    }
}
