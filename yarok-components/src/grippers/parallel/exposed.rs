//! What a [`ParallelGripper`] shows any plugin: its state (`state`), the grips it takes
//! (`command`) and the position a policy requests (its actuation, `…/position`).

use std::rc::Rc;

use yarok_core::BoxError;
use yarok_core::component::{Bind, Environment};

use super::{ParallelGripper, Request};

/// The gripper's state, as the 2F-85 reports it.
#[derive(serde::Serialize)]
struct GripperState {
    position: u8,
    moving: bool,
    object_detected: bool,
}

/// A grip: `move_to` a position (0 open to 255 closed), `open` or `close`; with a speed and a
/// force (0–255) when given.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct GripperCommand {
    move_to: Option<f64>,
    open: Option<bool>,
    close: Option<bool>,
    speed: Option<f64>,
    force: Option<f64>,
}

/// A 0–255 register value, or an error naming the field when `value` is not one.
fn byte(field: &str, value: f64) -> Result<u8, BoxError> {
    if value.fract() == 0.0 && (0.0..=255.0).contains(&value) {
        Ok(value as u8)
    } else {
        Err(format!("{field} {value} is not a whole number from 0 to 255").into())
    }
}

/// Publishes the gripper's `state` and takes its `command`s.
pub(super) fn expose<E: Environment>(bind: &mut Bind<E>, gripper: &ParallelGripper) {
    let shown = gripper.clone();
    bind.state("state", move || GripperState {
        position: shown.position(),
        moving: shown.is_moving(),
        object_detected: shown.object_detected(),
    });
    let commanded = gripper.clone();
    bind.command("command", move |command: GripperCommand| {
        run(&commanded, command)
    });
    let name = format!("{}/position", bind.path().trim_start_matches('/'));
    let (measured, read, requested) = (
        gripper.clone(),
        Rc::clone(&gripper.drive),
        Rc::clone(&gripper.drive),
    );
    bind.actuation(
        [(name, [0.0, 255.0])],
        move || vec![f64::from(measured.position())],
        move |_ahead| vec![read.requested().position],
        move |targets| {
            let position = targets[0].round();
            let request = requested.requested();
            if position != request.position {
                requested.request(Request {
                    position,
                    ..request
                });
            }
            Ok(())
        },
    );
}

fn run(gripper: &ParallelGripper, command: GripperCommand) -> Result<(), BoxError> {
    let grip = match command {
        GripperCommand {
            move_to: Some(position),
            ..
        } => gripper.move_to(byte("move_to", position)?),
        GripperCommand { open: Some(_), .. } => gripper.open(),
        GripperCommand { close: Some(_), .. } => gripper.close(),
        _ => return Err("a gripper takes move_to, open or close".into()),
    };
    let grip = match command.speed {
        Some(speed) => grip.speed(byte("speed", speed)?),
        None => grip,
    };
    match command.force {
        Some(force) => grip.force(byte("force", force)?),
        None => grip,
    }
    .start();
    Ok(())
}
