//! A turntable of your own: a disc on a hinge turned by a position servo, with a `sim` drive
//! (MuJoCo) and a `mock` drive (no physics: it is where it is told to be), composed beside
//! yarok's bundled components.

pub mod pan_tilt;

use std::cell::Cell;
use std::rc::Rc;

use yarok::prelude::*;

/// A turntable: `turn_to(radians)`, `angle()`.
#[derive(Clone)]
pub struct Turntable {
    turning: Rc<dyn Turning>,
}

impl std::fmt::Debug for Turntable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Turntable")
            .field("angle", &self.angle())
            .finish()
    }
}

/// How the turntable turns in one environment.
trait Turning {
    fn turn_to(&self, radians: f64);
    fn angle(&self) -> f64;
}

/// In `sim`: the servo turns the disc; the joint sensor says where it is.
struct Servo {
    servo: Actuator,
    angle: Sensor,
}

impl Turning for Servo {
    fn turn_to(&self, radians: f64) {
        self.servo.set(radians);
    }

    fn angle(&self) -> f64 {
        self.angle.value()
    }
}

/// In `mock`: no physics; the disc is where it was told to be.
struct Told {
    angle: Cell<f64>,
}

impl Turning for Told {
    fn turn_to(&self, radians: f64) {
        self.angle.set(radians);
    }

    fn angle(&self) -> f64 {
        self.angle.get()
    }
}

/// The turntable's config: the disc's radius (metres) and the servo's stiffness.
#[derive(Clone, serde::Serialize, serde::Deserialize)]
struct TurntableConfig {
    radius: f64,
    kp: f64,
}

impl Component for Turntable {
    fn declaration() -> Declaration {
        Declaration::new("turntable")
            .config(TurntableConfig {
                radius: 0.15,
                kp: 5.0,
            })
            .template(
                r#"<mujoco>
                     <worldbody>
                       <body name="disc" pos="0 0 0.02">
                         <joint name="hinge" axis="0 0 1" damping="0.2"/>
                         <geom type="cylinder" size="{radius} 0.01" mass="0.5"/>
                       </body>
                     </worldbody>
                     <actuator><position name="servo" joint="hinge" kp="{kp}" ctrlrange="-3.15 3.15"/></actuator>
                     <sensor><jointpos name="angle" joint="hinge"/></sensor>
                   </mujoco>"#,
            )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>();
    }
}

impl Interface<Sim> for Turntable {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Ok(Turntable {
            turning: Rc::new(Servo {
                servo: bind.actuator("servo")?,
                angle: bind.sensor("angle")?,
            }),
        })
    }
}

impl Interface<Mock> for Turntable {
    async fn bind(_bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Ok(Turntable {
            turning: Rc::new(Told {
                angle: Cell::new(0.0),
            }),
        })
    }
}

impl Turntable {
    /// Sets the angle (radians) the turntable turns to.
    pub fn turn_to(&self, radians: f64) {
        self.turning.turn_to(radians);
    }

    /// The angle it is at (radians).
    pub fn angle(&self) -> f64 {
        self.turning.angle()
    }
}

/// A table with a turntable on it.
#[derive(Debug)]
pub struct Showroom;

impl Component for Showroom {
    fn declaration() -> Declaration {
        Declaration::new("showroom").uses::<Turntable>().template(
            r#"<mujoco>
                 <worldbody>
                   <geom name="floor" type="plane" size="1 1 0.1"/>
                   <turntable name="table" radius="0.2"/>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

/// Turns the showroom's turntable a quarter turn and waits until it is there (within 0.01 rad,
/// at most 5 s of platform time); the angle it reached.
pub async fn quarter_turn(pl: Pl) -> Result<f64, BoxError> {
    let table: Turntable = pl.get("/table")?;
    let target = std::f64::consts::FRAC_PI_2;
    table.turn_to(target);
    pl.timeout(5.0, pl.wait(|| (table.angle() - target).abs() < 0.01))
        .await??;
    Ok(table.angle())
}
