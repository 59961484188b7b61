//! Two pendulums swing to targets, one behaviour each, sharing the ticks: the component and
//! behaviour of the README's "Write your first component" and "Let's make your robot move".
//!
//! ```text
//! cargo run --example pendulum_clock [-- --set /right/length=0.4]
//! cargo run --example pendulum_clock -- --set plugins/joints_csv/path=clock.csv
//! ```

use yarok::prelude::*;

/// A pendulum with a position servo: `swing_to(angle)`, `angle()`.
#[derive(Clone, Debug)]
pub struct Pendulum {
    servo: Actuator,
    angle: Sensor,
}

impl Component for Pendulum {
    fn declaration() -> Declaration {
        Declaration::new("pendulum")
            .default("length", 0.3)
            .default("kp", 20.0)
            .template(
                r#"<mujoco>
                 <worldbody>
                   <body name="arm" pos="0 0 1">
                     <joint name="hinge" axis="0 1 0" damping="0.5"/>
                     <geom type="capsule" fromto="0 0 0 0 0 -{length}" size="0.02"/>
                   </body>
                 </worldbody>
                 <actuator><position name="servo" joint="hinge" kp="{kp}"/></actuator>
                 <sensor><jointpos name="angle" joint="hinge"/></sensor>
               </mujoco>"#,
            )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for Pendulum {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Ok(Pendulum {
            servo: bind.actuator("servo")?,
            angle: bind.sensor("angle")?,
        })
    }
}

impl Pendulum {
    /// Sets the servo's target angle.
    pub fn swing_to(&self, radians: f64) {
        self.servo.set(radians);
    }

    /// The current angle, from the joint sensor.
    pub fn angle(&self) -> f64 {
        self.angle.value()
    }
}

/// A world with two pendulums, the second one longer.
struct Clock;

impl Component for Clock {
    fn declaration() -> Declaration {
        Declaration::new("clock").uses::<Pendulum>().template(
            r#"<mujoco><compiler angle="radian"/><worldbody>
                 <pendulum name="left"/>
                 <body name="right_mount" pos="0.5 0 0"><pendulum name="right" length="0.5"/></body>
               </worldbody></mujoco>"#,
        )
    }
}

async fn tick_tock(pl: Pl, name: &'static str) -> BehaviourResult {
    let pendulum: Pendulum = pl.get(name)?;
    for target in [0.5, -0.5, 0.0] {
        pendulum.swing_to(target);
        pl.wait(|| (pendulum.angle() - target).abs() < 0.01)
            .timeout(5.0)
            .await?;
        println!("{name} reached {target} rad at t = {:.2} s", pl.time());
        pl.wait_seconds(0.5).await?; // simulated seconds, not wall-clock seconds
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    yarok::platform()
        .world::<Clock>()
        .args(std::env::args_os().skip(1))? // e.g. --set /right/length=0.4
        .behaviour(|pl| tick_tock(pl, "left"))
        .behaviour(|pl| tick_tock(pl, "/right"))
        .run()?;
    Ok(())
}
