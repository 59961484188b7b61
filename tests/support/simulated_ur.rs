//! The fake UR controller's arm driven by the project's own simulated UR model: a platform on a
//! thread of its own runs a UR5e (or UR5) in real time; a script's `movej`/`movel`/`stopj`
//! becomes the simulated arm's `move_j`/`move_l`/`stop` with the speed and acceleration asked
//! for, so motions take physical time, accelerating and braking as a controller's do, and the
//! controller reports the simulated joints and speeds.
#![allow(dead_code)]

use std::ops::Deref;
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};

use yarok::components::robots::ur::{Arm, Ur5, Ur5e, pose_from_vector};
use yarok::core::runtime::PlatformThread;
use yarok::{Component, Declaration};

use yarok_test::ur_controller::motion::{ArmCommand, ArmMotion, ArmState};

/// A UR5e alone, at `/arm`.
pub(crate) struct Ur5eAlone;

impl Component for Ur5eAlone {
    fn declaration() -> Declaration {
        Declaration::new("ur5e_alone")
            .uses::<Ur5e>()
            .template(r#"<mujoco><worldbody><ur5e name="arm"/></worldbody></mujoco>"#)
    }
}

/// A UR5 alone, at `/arm`.
pub(crate) struct Ur5Alone;

impl Component for Ur5Alone {
    fn declaration() -> Declaration {
        Declaration::new("ur5_alone")
            .uses::<Ur5>()
            .template(r#"<mujoco><worldbody><ur5 name="arm"/></worldbody></mujoco>"#)
    }
}

/// Starts a simulated arm at rest at `start`, following `commands` and publishing its state.
type Spawn = fn([f64; 6], Arc<Mutex<ArmState>>, Receiver<ArmCommand>) -> PlatformThread;

/// A simulated UR arm behind the fake controller, running until dropped.
pub(crate) struct SimulatedArm {
    spawn: Spawn,
    state: Arc<Mutex<ArmState>>,
    commands: Sender<ArmCommand>,
    running: Option<PlatformThread>,
}

impl SimulatedArm {
    /// A simulated UR5e at rest at `start`.
    pub(crate) fn ur5e(start: [f64; 6]) -> Box<Self> {
        Box::new(Self::new(spawn::<Ur5eAlone, Ur5e>, start))
    }

    /// A simulated UR5 at rest at `start`.
    pub(crate) fn ur5(start: [f64; 6]) -> Box<Self> {
        Box::new(Self::new(spawn::<Ur5Alone, Ur5>, start))
    }

    fn new(spawn: Spawn, start: [f64; 6]) -> Self {
        let state = Arc::new(Mutex::new(at_rest(start)));
        let (commands, receiver) = mpsc::channel();
        let running = spawn(start, Arc::clone(&state), receiver);
        Self {
            spawn,
            state,
            commands,
            running: Some(running),
        }
    }

    fn end(&mut self) {
        if let Some(running) = self.running.take() {
            running.stop();
            running.join().expect("the simulated arm ran");
        }
    }
}

impl Drop for SimulatedArm {
    fn drop(&mut self) {
        self.end();
    }
}

impl ArmMotion for SimulatedArm {
    fn state(&self) -> ArmState {
        *self.state.lock().unwrap()
    }

    fn command(&mut self, command: ArmCommand) {
        let _ended_only_when_dropped = self.commands.send(command);
    }

    /// Starts the simulation again with the arm at `q`.
    fn place(&mut self, q: [f64; 6]) {
        self.end();
        *self = Self::new(self.spawn, q);
    }
}

fn at_rest(q: [f64; 6]) -> ArmState {
    ArmState {
        q,
        qd: [0.0; 6],
        target: q,
        moving: false,
    }
}

/// World `W`'s arm `A` at `start`, paced to the wall clock, following `commands` after every
/// step.
fn spawn<W: Component, A: Deref<Target = Arm> + Clone + 'static>(
    start: [f64; 6],
    state: Arc<Mutex<ArmState>>,
    commands: Receiver<ArmCommand>,
) -> PlatformThread {
    PlatformThread::spawn(move || {
        let start = start.map(|q| q.to_string()).join(", ");
        yarok::platform()
            .world::<W>()
            .ctrl_c(false)
            .set("platform/realtime=true")
            .and_then(|builder| builder.set(&format!("/arm/start=[{start}]")))
            .expect("the simulated arm's settings are valid")
            .behaviour(move |pl| async move {
                let arm: A = pl.get("/arm")?;
                let mut target = arm.q();
                pl.wait(|| {
                    follow(&arm, &commands, &mut target);
                    *state.lock().unwrap() = measure(&arm, target);
                    false
                })
                .await?;
                Ok(())
            })
    })
}

/// Starts the motions `commands` ask for (those the arm cannot make are left, as the
/// controller's refusal would leave the arm); `target` is where the last one ends.
fn follow(arm: &Arm, commands: &Receiver<ArmCommand>, target: &mut [f64; 6]) {
    for command in commands.try_iter() {
        match command {
            ArmCommand::Joints {
                to,
                speed,
                acceleration,
            } => {
                if arm
                    .move_j(to)
                    .speed(speed)
                    .acceleration(acceleration)
                    .start()
                    .is_ok()
                {
                    *target = to;
                }
            }
            ArmCommand::Line {
                pose,
                tcp,
                speed,
                acceleration,
            } => {
                // The script's TCP pose, as the pose of the simulated arm's own TCP.
                let flange = pose_from_vector(pose) * pose_from_vector(tcp).inverse();
                let goal = flange * arm.kinematics().tcp;
                let started = arm
                    .move_l(goal)
                    .speed(speed)
                    .acceleration(acceleration)
                    .start();
                if let (Ok(()), Ok(end)) = (started, arm.kinematics().nearest(&goal, &arm.q())) {
                    *target = end;
                }
            }
            ArmCommand::Servo { to, seconds } => {
                if arm.servo_j(to, seconds).is_ok() {
                    *target = to;
                }
            }
            ArmCommand::Stop => arm.stop(),
        }
    }
}

fn measure(arm: &Arm, target: [f64; 6]) -> ArmState {
    let moving = arm.is_moving();
    ArmState {
        q: arm.q(),
        qd: arm.qd(),
        target: if moving { target } else { arm.q() },
        moving,
    }
}
