//! [`Motions`]: what an arm's controller knows of its motions — the one under way, and how the
//! last one that ended, ended — and [`Running`], a motion under way along its profile.

use super::profile::Profile;

/// How close (radians, every joint) counts as arrived.
pub const ARRIVED_RAD: f64 = 1e-3;

/// How close (metres) counts as arrived for a pose (an arm's `is_at_pose`); its rotation within
/// [`ARRIVED_RAD`].
pub const ARRIVED_M: f64 = 1e-3;

/// URScript's `movej` defaults, every arm's: joint speed (rad/s) and acceleration (rad/s²).
pub const MOVE_J_DEFAULTS: (f64, f64) = (1.05, 1.4);

/// URScript's `movel` defaults, every arm's: tool speed (m/s) and acceleration (m/s²).
pub const MOVE_L_DEFAULTS: (f64, f64) = (0.25, 1.2);

/// Seconds after its profile ends that a motion may take to settle within [`ARRIVED_RAD`]
/// before it counts as failed (something blocks the arm).
pub const SETTLE_SECONDS: f64 = 0.5;

/// Whether every joint of `q` is within [`ARRIVED_RAD`] of `target` (and there are as many).
pub(crate) fn within(q: &[f64], target: &[f64]) -> bool {
    q.len() == target.len()
        && q.iter()
            .zip(target)
            .all(|(a, b)| (a - b).abs() < ARRIVED_RAD)
}

/// The ways a motion ends without arriving that every arm shares: an arm's motion error.
pub(crate) trait MotionEnding: Clone {
    /// The arm's joints, as its errors carry them.
    type Joints;
    /// The arm's `stop` stopped it, or its future was dropped.
    fn stopped() -> Self;
    /// A newer motion replaced it.
    fn replaced() -> Self;
    /// Its profile ended `seconds` ago but the arm, `at`, did not settle at `target`.
    fn not_arrived(target: Self::Joints, at: Self::Joints, seconds: f64) -> Self;
}

/// A motion under way: its `path` (the arm's own kind) run along `profile` from platform time
/// `started` toward the joints `target`.
pub(crate) struct Running<P, J> {
    pub(crate) id: u64,
    pub(crate) path: P,
    pub(crate) profile: Profile,
    pub(crate) started: f64,
    pub(crate) target: J,
    pub(crate) stopping: bool,
}

impl<P, J: AsRef<[f64]> + Clone> Running<P, J> {
    /// How the motion ends now that its profile is over, the arm `at`: `None` while it settles.
    pub(crate) fn settled<E: MotionEnding<Joints = J>>(
        &self,
        at: J,
        now: f64,
    ) -> Option<Result<(), E>> {
        if self.stopping {
            Some(Err(E::stopped()))
        } else if within(at.as_ref(), self.target.as_ref()) {
            Some(Ok(()))
        } else if now - (self.started + self.profile.duration()) > SETTLE_SECONDS {
            Some(Err(E::not_arrived(self.target.clone(), at, SETTLE_SECONDS)))
        } else {
            None
        }
    }
}

/// A controller's motions: at most one under way, numbered in the order they start.
pub(crate) struct Motions<P, J, E> {
    under_way: Option<Running<P, J>>,
    next_id: u64,
    /// How the last motion that ended, ended.
    ended: Option<(u64, Result<(), E>)>,
}

impl<P, J, E: MotionEnding> Motions<P, J, E> {
    pub(crate) fn new() -> Self {
        Self {
            under_way: None,
            next_id: 0,
            ended: None,
        }
    }

    /// Whether a motion is under way.
    pub(crate) fn is_moving(&self) -> bool {
        self.under_way.is_some()
    }

    /// Starts a motion along `path` and `profile` from `now` toward `target`, replacing the one
    /// under way; its id.
    pub(crate) fn start(&mut self, path: P, profile: Profile, now: f64, target: J) -> u64 {
        let id = self.next_id;
        self.next_id += 1;
        if let Some(replaced) = self.under_way.take() {
            self.ended = Some((replaced.id, Err(E::replaced())));
        }
        self.under_way = Some(Running {
            id,
            path,
            profile,
            started: now,
            target,
            stopping: false,
        });
        id
    }

    /// Stops the motion under way at `now` (only motion `id`, if given): it decelerates along
    /// its path at its profile's acceleration. The motion, if it begins to stop.
    pub(crate) fn stop(&mut self, id: Option<u64>, now: f64) -> Option<&Running<P, J>> {
        let motion = self.under_way.as_mut()?;
        if motion.stopping || id.is_some_and(|id| id != motion.id) {
            return None;
        }
        let (along, speed) = motion.profile.at(now - motion.started);
        motion.profile = Profile::stopping(along, speed, motion.profile.acceleration());
        motion.started = now;
        motion.stopping = true;
        Some(motion)
    }

    /// How motion `id` is: `None` while under way.
    pub(crate) fn outcome(&self, id: u64) -> Option<Result<(), E>> {
        match (&self.under_way, &self.ended) {
            (Some(motion), _) if motion.id == id => None,
            (_, Some((ended, outcome))) if *ended == id => Some(outcome.clone()),
            _ => Some(Err(E::replaced())),
        }
    }

    /// The motion under way, taken out to advance it: [`Motions::keep`] or [`Motions::end`] it.
    pub(crate) fn take(&mut self) -> Option<Running<P, J>> {
        self.under_way.take()
    }

    /// Puts back a motion taken out that goes on.
    pub(crate) fn keep(&mut self, motion: Running<P, J>) {
        self.under_way = Some(motion);
    }

    /// Ends a motion taken out, as `outcome`.
    pub(crate) fn end(&mut self, motion: Running<P, J>, outcome: Result<(), E>) {
        self.ended = Some((motion.id, outcome));
    }

    /// Ends the motion under way, if any, as stopped (the world went back to its start).
    pub(crate) fn abandon(&mut self) {
        if let Some(motion) = self.under_way.take() {
            self.end(motion, Err(E::stopped()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robots::ur::MotionError;

    fn motions() -> Motions<&'static str, Vec<f64>, crate::robots::serial::SerialMotionError> {
        Motions::new()
    }

    #[test]
    fn a_newer_motion_replaces_the_one_under_way() {
        let mut motions = motions();
        let first = motions.start(
            "first",
            Profile::rest_to_rest(1.0, 1.0, 1.0),
            0.0,
            vec![1.0],
        );
        assert_eq!(motions.outcome(first), None);
        let second = motions.start(
            "second",
            Profile::rest_to_rest(1.0, 1.0, 1.0),
            0.5,
            vec![2.0],
        );
        assert_ne!(first, second);
        assert_eq!(motions.outcome(first), Some(Err(MotionEnding::replaced())));
        assert_eq!(motions.outcome(second), None);
        motions.abandon();
        assert_eq!(motions.outcome(second), Some(Err(MotionEnding::stopped())));
        assert!(!motions.is_moving());
    }

    #[test]
    fn a_stop_decelerates_from_where_the_motion_is_once_and_only_the_motion_named() {
        let mut motions = motions();
        let id = motions.start(
            "line",
            Profile::rest_to_rest(10.0, 1.0, 2.0),
            0.0,
            vec![10.0],
        );
        assert!(motions.stop(Some(id + 1), 1.0).is_none());
        let stopping = motions.stop(Some(id), 1.0).expect("the motion named stops");
        // One second in at 2 rad/s² capped at 1 rad/s: 0.75 along at full speed.
        assert_eq!(stopping.profile.at(0.0), (0.75, 1.0));
        assert_eq!(stopping.profile.duration(), 0.5);
        assert!(
            motions.stop(None, 1.2).is_none(),
            "a stopping motion stops once"
        );
    }

    #[test]
    fn a_motion_arrives_within_the_tolerance_or_fails_after_settling() {
        let mut motions: Motions<(), [f64; 6], MotionError> = Motions::new();
        motions.start((), Profile::rest_to_rest(1.0, 1.0, 1.0), 0.0, [1.0; 6]);
        let motion = motions.take().expect("under way");
        let end = motion.profile.duration();
        let near = [1.0 + ARRIVED_RAD / 2.0; 6];
        assert_eq!(motion.settled::<MotionError>(near, end), Some(Ok(())));
        let off = [1.1; 6];
        assert_eq!(
            motion.settled::<MotionError>(off, end + SETTLE_SECONDS / 2.0),
            None
        );
        assert_eq!(
            motion.settled::<MotionError>(off, end + SETTLE_SECONDS * 2.0),
            Some(Err(MotionError::NotArrived {
                target: [1.0; 6],
                at: off,
                seconds: SETTLE_SECONDS,
            }))
        );
    }
}
