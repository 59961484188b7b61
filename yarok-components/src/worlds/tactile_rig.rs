//! [`TactileRigWorld`]: a printer pressing an indenter into a tactile sensor, to collect
//! tactile data.

use image::RgbImage;
use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces};
use yarok_core::time::{Clock, WaitError};
use yarok_mjc::{DepthImage, Sim};

use super::EmptyWorld;
use crate::robots::{AnetA30, WORK_VOLUME_MM};
use crate::tactile_sensors::{Contact, Digit, GelSight2014, GelTip, TactileError, TactileSensor};

/// A printer (an [`AnetA30`] at the world's origin, its coordinates the world's in millimetres)
/// whose head carries an indenter, over an upright tactile sensor: a rig that presses the
/// indenter into the gel at chosen points and depths, as the GelTip simulation dataset was
/// collected. [`TactileRigWorld::press`] places the head exactly and returns the sensor's next
/// frame, so a sample depends only on its press, not on the presses before it: rigs on several
/// threads collect the same samples, byte for byte, as one rig does.
///
/// Config: `sensor` (`"geltip"`, default; `"digit"`; `"gelsight"`), `sensor_pos` (metres,
/// default 0.16, 0.16, 0: under the middle of the work volume), `indenter` (an MJCF geom type,
/// default `"sphere"`) and `indenter_size` (its MJCF size, default 4 mm radius; the last value is
/// the tip's height above its centre), `parallel` (the sensor's model across threads: on by
/// default with the `parallel` feature; turn it off when rigs run on every core), `pressing`
/// (`"placed"`, default: the indenter passes through the gel and a press is exactly as deep as
/// placed; `"force"`: it collides with the gel, which sinks as its elastomer law says, for
/// [`TactileRigWorld::press_with_force`]).
///
/// Paths: `/printer`, `/sensor`. Environment: `sim`.
///
/// ```
/// use yarok_components::worlds::{Press, TactileRigWorld};
/// use yarok_core::runtime::Platform;
/// use yarok_mjc::{Sim, SimBackend};
///
/// Platform::builder()
///     .world::<TactileRigWorld>()
///     .backend::<Sim>(SimBackend::from_settings)
///     .behaviour(|pl| async move {
///         let rig: TactileRigWorld = pl.get("/")?;
///         let sample = rig.press(Press { at: [0.0, 0.0], depth: 0.001 }).await?;
///         assert!((sample.contact.max_indentation - 0.001).abs() < 1e-4);
///         assert_eq!(sample.image.dimensions(), (320, 240));
///         Ok(())
///     })
///     .run()?;
/// # Ok::<(), yarok_core::runtime::RuntimeError>(())
/// ```
#[derive(Debug, Clone)]
pub struct TactileRigWorld {
    printer: AnetA30,
    sensor: TactileSensor,
    sensor_kind: String,
    /// Where the sensor stands (metres).
    sensor_pos: [f64; 3],
    /// Whether the indenter collides with the gel (`pressing = "force"`).
    pressing_by_force: bool,
    clock: Clock,
}

/// The stiffness (N/m) of the printer's axis servos by default: a force-controlled press's
/// first guess of how far past the surface to aim for a force.
const SERVO_STIFFNESS: f64 = 2000.0;

/// A press of the rig's indenter: where across the sensor's axis (metres, in the sensor's x and
/// y) and how deep below the untouched gel's surface there (metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Press {
    /// The indenter tip's offset across the sensor's axis.
    pub at: [f64; 2],
    /// How deep the tip goes below the gel's surface.
    pub depth: f64,
}

/// What the rig records for a press: the sensor's frame and depth, what it feels, and where the
/// printer's head was.
#[derive(Debug, Clone)]
pub struct Sample {
    /// The press.
    pub press: Press,
    /// The printer head's position (millimetres).
    pub head: [f64; 3],
    /// The sensor's image.
    pub image: RgbImage,
    /// The depth its camera saw (metres along its axis).
    pub depth: DepthImage,
    /// What it felt.
    pub contact: Contact,
}

/// Why a press could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PressError {
    /// The press is not over the gel, or its depth is not a finite number.
    #[error("no press at {at:?} m, {depth} m deep: {reason}")]
    Impossible {
        /// Where the press was asked for.
        at: [f64; 2],
        /// How deep.
        depth: f64,
        /// What is wrong.
        reason: &'static str,
    },
    /// The platform stopped while the press waited for the sensor's frame.
    #[error(transparent)]
    Wait(#[from] WaitError),
    /// The sensor has no depth to sample (a real one).
    #[error(transparent)]
    Sensor(#[from] TactileError),
}

impl TactileRigWorld {
    /// The printer.
    pub fn printer(&self) -> &AnetA30 {
        &self.printer
    }

    /// The tactile sensor.
    pub fn sensor(&self) -> &TactileSensor {
        &self.sensor
    }

    /// Which sensor the rig holds: `"geltip"`, `"digit"` or `"gelsight"` (config `sensor`).
    pub fn sensor_kind(&self) -> &str {
        &self.sensor_kind
    }

    /// Places the printer's head so that the indenter presses as `press` says (see
    /// [`AnetA30::place`]), and returns the sensor's first frame after that.
    ///
    /// # Errors
    ///
    /// [`PressError::Impossible`] for a press off the gel, NaN or negative, or out of the
    /// printer's reach; [`PressError::Wait`] when the platform stops meanwhile;
    /// [`PressError::Sensor`] for a sensor without depth (a real one).
    ///
    /// # Cancel safety
    ///
    /// Dropping the future leaves the head where it was placed.
    pub async fn press(&self, press: Press) -> Result<Sample, PressError> {
        let head = self.head_for(press)?;
        let placed = self.printer.place(head);
        let placed_at = self.clock.time();
        self.clock
            .wait(|| self.sensor.frame_time() > placed_at)
            .await?;
        Ok(Sample {
            press,
            head: placed,
            image: self.sensor.read(),
            depth: self.sensor.read_depth()?,
            contact: self.sensor.contact()?,
        })
    }

    /// Presses the indenter at `at` (metres across the sensor's axis) with a normal force of
    /// `newtons`, as a force-controlled press would: the head's servo target is lowered past
    /// the gel's surface until MuJoCo's contact force on the gel is within 2 % of the force
    /// asked (at most 30 corrections of 0.1 s each; the nearest is kept). Needs
    /// `pressing = "force"`, in which the indenter collides with the gel. Returns the sensor's
    /// first frame after the force settles; its `press.depth` is how deep the sensor felt it.
    ///
    /// # Errors
    ///
    /// As [`TactileRigWorld::press`]; [`PressError::Impossible`] also when the indenter passes
    /// through the gel (`pressing = "placed"`) or the force is not a finite number > 0.
    ///
    /// # Cancel safety
    ///
    /// Dropping the future leaves the head pressing with its latest target.
    pub async fn press_with_force(&self, at: [f64; 2], newtons: f64) -> Result<Sample, PressError> {
        let impossible = |reason| PressError::Impossible {
            at,
            depth: f64::NAN,
            reason,
        };
        if !(newtons > 0.0 && newtons.is_finite()) {
            return Err(impossible("the force must be a finite number > 0"));
        }
        if !self.pressing_by_force {
            return Err(impossible(
                "the indenter passes through the gel: set pressing = \"force\"",
            ));
        }
        let touching = self.head_for(Press { at, depth: 0.0 })?;
        self.printer.place(touching);
        let mut target = touching;
        for _ in 0..30 {
            self.clock.wait_seconds(0.1).await?;
            let felt = self.sensor.contact()?.force;
            if (felt - newtons).abs() <= 0.02 * newtons {
                break;
            }
            target[2] -= (newtons - felt) / SERVO_STIFFNESS * 1000.0;
            self.printer.move_to(target);
        }
        let settled_at = self.clock.time();
        self.clock
            .wait(|| self.sensor.frame_time() > settled_at)
            .await?;
        let contact = self.sensor.contact()?;
        Ok(Sample {
            press: Press {
                at,
                depth: contact.max_indentation,
            },
            head: self.printer.at(),
            image: self.sensor.read(),
            depth: self.sensor.read_depth()?,
            contact,
        })
    }

    /// The head's position (millimetres) for `press`.
    fn head_for(&self, press: Press) -> Result<[f64; 3], PressError> {
        let impossible = |reason| PressError::Impossible {
            at: press.at,
            depth: press.depth,
            reason,
        };
        let [x, y] = press.at;
        if !(press.depth >= 0.0 && press.depth.is_finite()) {
            return Err(impossible("the depth must be a finite number ≥ 0"));
        }
        let surface = self
            .sensor
            .surface_distance(x, y)
            .ok_or_else(|| impossible("the sensor has no gel there"))?;
        let [px, py, pz] = self.sensor_pos;
        let head = [px + x, py + y, pz + surface - press.depth].map(|m| m * 1000.0);
        if head
            .iter()
            .zip(WORK_VOLUME_MM)
            .any(|(mm, max)| !(0.0..=max).contains(mm))
        {
            return Err(impossible("the printer cannot reach it"));
        }
        Ok(head)
    }
}

/// The rig's config.
#[derive(serde::Serialize, serde::Deserialize)]
struct RigConfig {
    sensor: String,
    sensor_pos: [f64; 3],
    indenter: String,
    indenter_size: Vec<f64>,
    pressing: Pressing,
    parallel: bool,
}

/// How the indenter presses: to where it is placed, or until the sensor feels a force.
#[derive(Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
enum Pressing {
    Placed,
    Force,
}

impl Component for TactileRigWorld {
    fn declaration() -> Declaration {
        Declaration::new("tactile_rig_world")
            .extends::<EmptyWorld>()
            .uses::<AnetA30>()
            .uses::<GelTip>()
            .uses::<Digit>()
            .uses::<GelSight2014>()
            .config(RigConfig {
                sensor: "geltip".into(),
                sensor_pos: [0.16, 0.16, 0.0],
                indenter: "sphere".into(),
                indenter_size: vec![0.004],
                pressing: Pressing::Placed,
                parallel: cfg!(feature = "parallel"),
            })
            .template(include_str!("tactile_rig.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for TactileRigWorld {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let config: RigConfig = bind.config()?;
        let sensor = match config.sensor.as_str() {
            "geltip" => (*bind.child::<GelTip>("sensor")?).clone(),
            "digit" => (*bind.child::<Digit>("sensor")?).clone(),
            "gelsight" => (*bind.child::<GelSight2014>("sensor")?).clone(),
            other => {
                return Err(bind.error(format!(
                    "sensor must be \"geltip\", \"digit\" or \"gelsight\", not {other:?}"
                )));
            }
        };
        Ok(Self {
            pressing_by_force: config.pressing == Pressing::Force,
            printer: bind.child("printer")?,
            sensor,
            sensor_kind: config.sensor,
            sensor_pos: config.sensor_pos,
            clock: bind.clock(),
        })
    }
}
