//! Warnings reach the user without any set-up: the platform installs a subscriber that writes
//! them to standard error when the application has none, and MuJoCo's warnings (which MuJoCo
//! only counts) are among them. Checked from a child process, since a subscriber is
//! process-wide.

use std::process::Command;

use yarok::components::robots::AnetA30;
use yarok::components::worlds::PrinterWorld;
use yarok::prelude::*;

const CHILD: &str = "YAROK_WARNINGS_CHILD";

/// A free-spinning wheel with an unlimited motor.
#[derive(Clone)]
struct Wheel {
    motor: Actuator,
}

impl Component for Wheel {
    fn declaration() -> Declaration {
        Declaration::new("wheel").template(
            r#"<mujoco><worldbody><body name="hub"><joint name="axle"/><geom size="0.1"/></body></worldbody>
               <actuator><motor name="motor" joint="axle"/></actuator></mujoco>"#,
        )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for Wheel {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Ok(Wheel {
            motor: bind.actuator("motor")?,
        })
    }
}

/// The children: a NaN motor command, and a NaN printer target.
#[test]
fn nan_child() {
    match std::env::var(CHILD).as_deref() {
        Ok("motor") => yarok::platform()
            .world::<Wheel>()
            .behaviour(|pl| async move {
                let wheel: Wheel = pl.get("/")?;
                wheel.motor.set(f64::NAN);
                pl.wait_seconds(0.05).await?;
                Ok(())
            })
            .run()
            .unwrap(),
        Ok("printer") => yarok::platform()
            .world::<PrinterWorld>()
            .behaviour(|pl| async move {
                let printer: AnetA30 = pl.get("/printer")?;
                printer.move_to([f64::NAN, 10.0, 10.0]);
                pl.wait_seconds(0.01).await?;
                Ok(())
            })
            .run()
            .unwrap(),
        _ => {}
    }
}

fn stderr_of_child(case: &str) -> String {
    let output = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "nan_child", "--nocapture", "--test-threads=1"])
        .env(CHILD, case)
        .env_remove("RUST_LOG")
        .output()
        .unwrap();
    assert!(output.status.success(), "{output:?}");
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn a_nan_control_is_a_visible_warning() {
    let stderr = stderr_of_child("motor");
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("WARN") && l.contains("mujoco"))
        .collect();
    assert_eq!(warnings.len(), 1, "once, not every step:\n{stderr}");
    assert!(
        warnings[0].contains("mujoco") && warnings[0].contains("CTRL"),
        "{stderr}"
    );
}

#[test]
fn a_nan_printer_target_is_a_visible_warning() {
    let stderr = stderr_of_child("printer");
    assert!(
        stderr
            .lines()
            .any(|l| l.contains("WARN") && l.contains("NaN coordinate")),
        "{stderr}"
    );
}
