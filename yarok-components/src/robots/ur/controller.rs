//! [`Controller`]: runs an arm's motions as the UR controller does — after every step, the
//! joints due along the motion's path, fed to the servos with their speed and acceleration —
//! and tells how each motion ended.

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use nalgebra::Isometry3;
use yarok_core::time::Clock;

use crate::robots::motion::{Limits, MotionControl};
use crate::robots::motions::{Motions, Running};

use super::drive::{ArmDrive, Order, Setpoint};
use super::error::MotionError;
use super::kinematics::{IkError, Joints, Kinematics};
use super::path::Path;
use super::payload::Payload;
use super::streaming::{ServoLimits, Stream, within_speed};
use crate::robots::profile::Profile;

/// Where a motion goes, and how.
#[derive(Debug, Clone, Copy)]
pub(super) enum Goal {
    Joints(Joints),
    /// In joint space, to the joints that put the TCP at the pose.
    JointsFor(Isometry3<f64>),
    /// The TCP along a straight line.
    Line(Isometry3<f64>),
}

/// Runs an arm's motions.
pub(super) struct Controller {
    kinematics: Kinematics,
    clock: Clock,
    drive: Rc<dyn ArmDrive>,
    servo_limits: Cell<ServoLimits>,
    state: RefCell<State>,
}

struct State {
    /// What is commanded for the next step, with the payload set by
    /// [`Controller::set_payload`].
    setpoint: Setpoint,
    motions: Motions<Path, Joints, MotionError>,
    /// The streamed target being approached, when no motion is under way.
    stream: Option<Stream>,
    /// Where the last `servoj` of the stream told the arm's own controller to go.
    ordered: Joints,
    /// What stopped a stream (a real arm's safety stop, its power): streamed targets are
    /// refused with it until the stream is re-armed, even once the stop has cleared.
    stopped: Option<MotionError>,
}

/// The joints `t` seconds into `motion` (by inverse kinematics near `near` on a line), and
/// their speeds over the step of `dt` that follows.
fn reference(
    motion: &Running<Path, Joints>,
    t: f64,
    dt: f64,
    kinematics: &Kinematics,
    near: &Joints,
) -> Result<(Joints, Joints), IkError> {
    let (along, _) = motion.profile.at(t);
    let (ahead, _) = motion.profile.at(t + dt);
    let q = Path::joints_at(motion.path.point(along), kinematics, near)?;
    let next = Path::joints_at(motion.path.point(ahead), kinematics, &q)?;
    Ok((q, std::array::from_fn(|i| (next[i] - q[i]) / dt)))
}

impl Controller {
    /// A controller of `drive`, holding `start` until a motion comes.
    pub(super) fn new(
        clock: Clock,
        kinematics: Kinematics,
        drive: Rc<dyn ArmDrive>,
        start: Joints,
    ) -> Self {
        Self {
            kinematics,
            clock,
            drive,
            servo_limits: Cell::new(ServoLimits::default()),
            state: RefCell::new(State {
                setpoint: Setpoint {
                    q: start,
                    speed: [0.0; 6],
                    acceleration: [0.0; 6],
                    payload: None,
                },
                motions: Motions::new(),
                stream: None,
                ordered: start,
                stopped: None,
            }),
        }
    }

    pub(super) fn kinematics(&self) -> &Kinematics {
        &self.kinematics
    }

    /// Joint angles (radians).
    pub(super) fn q(&self) -> Joints {
        self.drive.q(&self.state.borrow().setpoint)
    }

    /// Joint speeds (rad/s).
    pub(super) fn qd(&self) -> Joints {
        self.drive.qd(&self.state.borrow().setpoint)
    }

    /// Unlocks a protective stop, where the drive has one.
    pub(super) async fn unlock_protective_stop(&self) -> Result<(), String> {
        self.drive.unlock_protective_stop().await
    }

    /// Whether a motion is under way.
    pub(super) fn is_moving(&self) -> bool {
        self.state.borrow().motions.is_moving()
    }

    /// After a step: the reference for the next one, and whether the motion has ended.
    pub(super) fn tick(&self) {
        self.advance(self.clock.time());
        self.command();
    }

    /// Moves the reference to where the motion, or the streamed target's approach, is due at
    /// `now` plus a step.
    fn advance(&self, now: f64) {
        let mut state = self.state.borrow_mut();
        let Some(motion) = state.motions.take() else {
            self.approach(&mut state, now);
            return;
        };
        let dt = self.clock.timestep();
        let t = now + dt - motion.started;
        let reference = match self.drive.halt() {
            Some(error) => Err(error),
            None => reference(&motion, t, dt, &self.kinematics, &state.setpoint.q)
                .map_err(MotionError::from),
        };
        let outcome = match reference {
            Err(error) => Some(Err(error)),
            Ok((q, speed)) => {
                let setpoint = &mut state.setpoint;
                let before = setpoint.q;
                setpoint.acceleration =
                    std::array::from_fn(|i| (speed[i] - (q[i] - before[i]) / dt) / dt);
                setpoint.q = q;
                setpoint.speed = speed;
                // A real arm's position not yet current is known again, or the run ends.
                if t >= motion.profile.duration() && self.drive.is_current() {
                    motion
                        .settled(self.drive.q(&state.setpoint), now)
                        .map(|outcome| outcome.map_err(|miss| self.explained(miss)))
                } else {
                    None
                }
            }
        };
        match outcome {
            Some(outcome) => {
                state.setpoint.speed = [0.0; 6];
                state.setpoint.acceleration = [0.0; 6];
                state.motions.end(motion, outcome);
            }
            None => state.motions.keep(motion),
        }
    }

    /// Moves the setpoint a step toward the streamed target, within the servo limits; a drive
    /// that cannot move ends the stream where the arm is.
    fn approach(&self, state: &mut State, now: f64) {
        let Some(stream) = state.stream else {
            return;
        };
        if let Some(halted) = self.drive.halt() {
            state.stream = None;
            state.stopped = Some(halted);
            let measured = self.drive.q(&state.setpoint);
            let setpoint = &mut state.setpoint;
            setpoint.q = measured;
            setpoint.speed = [0.0; 6];
            setpoint.acceleration = [0.0; 6];
            return;
        }
        let dt = self.clock.timestep();
        let setpoint = &mut state.setpoint;
        let (q, speed) = stream.step(
            &setpoint.q,
            &setpoint.speed,
            now,
            dt,
            &self.servo_limits.get(),
            &self.kinematics.limits,
        );
        setpoint.acceleration = std::array::from_fn(|i| (speed[i] - setpoint.speed[i]) / dt);
        setpoint.q = q;
        setpoint.speed = speed;
    }

    /// `miss` as the drive explains it: a motion whose connection dropped on the way is lost
    /// to that, not merely short of its target.
    fn explained(&self, miss: MotionError) -> MotionError {
        match (miss, self.drive.interruption()) {
            (MotionError::NotArrived { target, at, .. }, Some(cause)) => {
                MotionError::ConnectionLost { cause, target, at }
            }
            (miss, _) => miss,
        }
    }

    /// The world went back to its start (an episode began): the arm holds `start` again, and a
    /// motion under way ends as stopped.
    pub(super) fn restart(&self, start: Joints) {
        self.hold(start);
        self.command();
    }

    /// Ends a stream of targets, and re-arms one a stop ended: the next target begins one from
    /// where the arm is measured.
    pub(super) fn end_stream(&self) {
        let mut state = self.state.borrow_mut();
        state.stream = None;
        state.stopped = None;
        drop(state);
        self.drive.rearm();
    }

    /// Ends a motion under way as stopped, and a stream, and holds `q` at rest.
    fn hold(&self, q: Joints) {
        let mut state = self.state.borrow_mut();
        state.motions.abandon();
        state.stream = None;
        state.stopped = None;
        let setpoint = &mut state.setpoint;
        setpoint.q = q;
        setpoint.speed = [0.0; 6];
        setpoint.acceleration = [0.0; 6];
    }

    /// Streams `target`, due in `seconds`, as URScript's `servoj` does: a motion under way
    /// ends as stopped, and from the next step the setpoint approaches the target within the
    /// servo limits (a stream begins where the arm is measured, at rest, unless it takes over
    /// a motion's setpoint). The drive is ordered where the setpoint will be when it is due,
    /// no farther from its last order than the speed limits reach in `seconds`.
    /// Refused, the stream ended, while the drive cannot move (a real arm's safety stop), and
    /// after that until [`Controller::end_stream`] re-arms it: the stream then begins again
    /// where the arm is.
    pub(super) fn servo(&self, target: Joints, seconds: f64) -> Result<(), MotionError> {
        self.joint_path(target, target)?;
        if let Some(stopped) = self.state.borrow().stopped.clone() {
            return Err(MotionError::StreamStopped {
                cause: Box::new(stopped),
            });
        }
        if let Some(halted) = self.drive.halt() {
            let mut state = self.state.borrow_mut();
            state.stream = None;
            state.stopped = Some(halted.clone());
            return Err(halted);
        }
        let now = self.clock.time();
        let dt = self.clock.timestep();
        let limits = self.servo_limits.get();
        let mut state = self.state.borrow_mut();
        let took_over_a_motion = state.motions.is_moving();
        state.motions.abandon();
        if state.stream.is_none() {
            if !took_over_a_motion {
                let measured = self.drive.q(&state.setpoint);
                let setpoint = &mut state.setpoint;
                setpoint.q = measured;
                setpoint.speed = [0.0; 6];
                setpoint.acceleration = [0.0; 6];
            }
            state.ordered = state.setpoint.q;
        }
        let stream = Stream::next(state.stream.as_ref(), target, now, seconds, dt, &limits);
        state.stream = Some(stream);
        let due = stream.due_from(
            &state.setpoint.q,
            &state.setpoint.speed,
            now,
            dt,
            &limits,
            &self.kinematics.limits,
        );
        // However late this target came, the arm's own controller is asked no faster than the
        // limits from where the last `servoj` sent it.
        let ordered = within_speed(&state.ordered, &due, seconds, &limits);
        state.ordered = ordered;
        drop(state);
        self.drive.order(Order::ServoJ {
            target: ordered,
            seconds,
            max_speed: limits.speed(),
        });
        self.command();
        Ok(())
    }

    /// The limits streamed targets are approached within.
    pub(super) fn servo_limits(&self) -> ServoLimits {
        self.servo_limits.get()
    }

    /// Sets the limits streamed targets are approached within, from the next step.
    pub(super) fn set_servo_limits(&self, limits: ServoLimits) {
        self.servo_limits.set(limits);
    }

    /// Where the joints are commanded to be `ahead` seconds from now: a streamed target, or
    /// where the motion under way is due then (its end, past it), or the setpoint held.
    pub(super) fn target_in(&self, ahead: f64) -> Joints {
        let mut state = self.state.borrow_mut();
        if let Some(stream) = state.stream {
            return stream.target();
        }
        let Some(motion) = state.motions.take() else {
            return state.setpoint.q;
        };
        let t = (self.clock.time() + ahead - motion.started).min(motion.profile.duration());
        let (along, _) = motion.profile.at(t);
        let due = Path::joints_at(
            motion.path.point(along),
            &self.kinematics,
            &state.setpoint.q,
        );
        state.motions.keep(motion);
        due.unwrap_or(state.setpoint.q)
    }

    /// The joints commanded for the next step.
    pub(super) fn setpoint(&self) -> Joints {
        self.state.borrow().setpoint.q
    }

    /// Commands the setpoint to the drive.
    pub(super) fn command(&self) {
        self.drive.command(&self.state.borrow().setpoint);
    }

    /// Sets what the arm carries: fed forward in `sim`, ordered of a real arm.
    pub(super) fn set_payload(&self, payload: Payload) {
        self.state.borrow_mut().setpoint.payload = Some(payload);
        self.drive.order(Order::SetPayload(payload));
        self.command();
    }

    fn joint_path(&self, from: Joints, target: Joints) -> Result<Path, MotionError> {
        let inside = target
            .iter()
            .zip(&self.kinematics.limits)
            .all(|(q, (lower, upper))| q.is_finite() && (lower..=upper).contains(&q));
        if inside {
            Ok(Path::Joints { from, to: target })
        } else {
            Err(MotionError::InvalidTarget { target })
        }
    }
}

impl MotionControl for Controller {
    type Goal = Goal;
    type Error = MotionError;

    /// Starts a motion to `to`, after checking the whole path; its id.
    fn start(&self, goal: Self::Goal, limits: Limits) -> Result<u64, MotionError> {
        let Limits {
            speed,
            acceleration,
            ..
        } = limits;
        if !(speed > 0.0 && acceleration > 0.0 && speed.is_finite() && acceleration.is_finite()) {
            return Err(MotionError::InvalidLimits {
                speed,
                acceleration,
            });
        }
        let mut state = self.state.borrow_mut();
        let from = state.setpoint.q;
        let path = match goal {
            Goal::Joints(target) => self.joint_path(from, target)?,
            Goal::JointsFor(pose) => {
                self.joint_path(from, self.kinematics.nearest(&pose, &from)?)?
            }
            Goal::Line(pose) => Path::Line {
                from: self.kinematics.forward(&from),
                to: pose,
            },
        };
        let target = path.check(&self.kinematics, &from)?;
        let profile = Profile::rest_to_rest(path.length(), speed, acceleration);
        let id = state
            .motions
            .start(path, profile, self.clock.time(), target);
        drop(state);
        self.drive.order(match path {
            Path::Line { to, .. } => Order::MoveL {
                pose: to,
                tcp: self.kinematics.tcp,
                speed,
                acceleration,
            },
            Path::Joints { .. } => Order::MoveJ {
                target,
                speed,
                acceleration,
            },
        });
        self.advance(self.clock.time());
        self.command();
        Ok(id)
    }

    /// Stops the motion under way (only motion `id`, if given), or a stream (when no `id` is
    /// given): it decelerates to rest within the servo limits.
    fn stop(&self, id: Option<u64>) {
        let mut state = self.state.borrow_mut();
        if let (None, Some(stream)) = (id, state.stream) {
            let setpoint = &state.setpoint;
            let stopping = stream.stopping(&setpoint.q, &setpoint.speed, &self.servo_limits.get());
            state.stream = Some(stopping);
            drop(state);
            self.drive.order(Order::StopJ {
                deceleration: self
                    .servo_limits
                    .get()
                    .acceleration()
                    .into_iter()
                    .fold(f64::MAX, f64::min),
            });
            return;
        }
        if let Some(motion) = state.motions.stop(id, self.clock.time()) {
            let deceleration = motion.profile.acceleration();
            self.drive.order(match motion.path {
                Path::Line { .. } => Order::StopL { deceleration },
                Path::Joints { .. } => Order::StopJ { deceleration },
            });
        }
    }

    /// How motion `id` is: `None` while under way.
    fn outcome(&self, id: u64) -> Option<Result<(), MotionError>> {
        self.state.borrow().motions.outcome(id)
    }

    fn clock(&self) -> &Clock {
        &self.clock
    }
}
