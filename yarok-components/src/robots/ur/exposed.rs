//! What an [`Arm`] shows any plugin: its state (`state`), the motions it takes (`command`) and
//! the joint targets a policy streams (its actuation).

use std::cell::Cell;
use std::rc::Rc;

use yarok_core::BoxError;
use yarok_core::component::{Bind, Environment};

use super::{Arm, Joints, pose_to_vector};

/// The arm's actuators, as yarok's templates and Menagerie's UR5e name them.
const ACTUATORS: [&str; 6] = super::ArmNames::YAROK.actuators;

/// The longest a streamed target is given to be reached in (seconds), however long the policy
/// took to send the next.
const LONGEST_SERVO_S: f64 = 0.2;

/// The arm's state: joint angles and speeds, and the TCP as a UR pose vector.
#[derive(serde::Serialize)]
struct ArmState {
    q: Joints,
    qd: Joints,
    tcp: [f64; 6],
}

/// A motion: `move_j` to joints, `move_l` to a TCP pose vector, or `stop`; with the speed and
/// acceleration of `movej`/`movel` when given.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ArmCommand {
    move_j: Option<Joints>,
    move_l: Option<[f64; 6]>,
    stop: Option<bool>,
    speed: Option<f64>,
    acceleration: Option<f64>,
}

/// Publishes the arm's `state` and takes its `command`s.
pub(super) fn expose<E: Environment>(bind: &mut Bind<E>, arm: &Arm) {
    let shown = arm.clone();
    bind.state("state", move || ArmState {
        q: shown.q(),
        qd: shown.qd(),
        tcp: pose_to_vector(&shown.tcp_pose()),
    });
    let commanded = arm.clone();
    bind.command("command", move |command: ArmCommand| {
        run(&commanded, command)
    });
    let prefix = bind.path().trim_start_matches('/').to_owned();
    let limits = arm.kinematics().limits;
    let actuators = std::array::from_fn::<_, 6, _>(|i| {
        (format!("{prefix}/{}", ACTUATORS[i]), limits[i].into())
    });
    let (measured, read, streamed, clock) = (arm.clone(), arm.clone(), arm.clone(), bind.clock());
    // When the previous target was given: a stream's period. An episode's first target has
    // none (the same start, the same stream, episode after episode).
    let last_target = Rc::new(Cell::new(f64::NEG_INFINITY));
    let forgotten = Rc::clone(&last_target);
    bind.on_restart(move || forgotten.set(f64::NEG_INFINITY));
    bind.actuation(
        actuators,
        move || measured.q().to_vec(),
        move |ahead| read.target_in(ahead).to_vec(),
        move |targets| {
            let now = clock.time();
            let previous = last_target.replace(now);
            // An episode's first target has no period: it is reached as soon as the servo
            // limits allow.
            let since = if previous.is_finite() {
                (now - previous).min(LONGEST_SERVO_S)
            } else {
                0.0
            };
            let target = std::array::from_fn(|i| targets[i]);
            streamed.servo_j(target, since.max(clock.timestep()))?;
            Ok(())
        },
    );
}

fn run(arm: &Arm, command: ArmCommand) -> Result<(), BoxError> {
    let motion = match command {
        ArmCommand {
            move_j: Some(q), ..
        } => arm.move_j(q),
        ArmCommand {
            move_l: Some(pose), ..
        } => arm.move_l_vector(pose),
        ArmCommand { stop: Some(_), .. } => {
            arm.stop();
            return Ok(());
        }
        _ => return Err("an arm takes move_j, move_l or stop".into()),
    };
    let motion = match command.speed {
        Some(speed) => motion.speed(speed),
        None => motion,
    };
    let motion = match command.acceleration {
        Some(acceleration) => motion.acceleration(acceleration),
        None => motion,
    };
    motion.start()?;
    Ok(())
}
