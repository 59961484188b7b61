//! Streamed joint targets (a policy's actions, URScript's `servoj`) approached within the arm's
//! joint speed and acceleration limits: [`ServoLimits`] and the [`Stream`] a controller steps.
//!
//! Each target is due at the end of its period (the time since the previous one, as
//! `servoj`'s `t`): the setpoint moves toward it in a straight line in joint space, no joint
//! faster than its speed limit or speeding up or slowing down faster than its acceleration
//! limit, and always slow enough to stop at the target (or, while the targets move at a speed
//! the arm can keep, to go on at that speed). So a target farther than a period allows is
//! approached at the limits and reached at rest, and a stream of nearby targets is followed
//! without lag. When moving targets stop coming (a late policy) the arm comes to rest within
//! its acceleration limit, past the last target by at most what stopping from its speed takes
//! (v²/2a: 0.08 rad from 1 rad/s at 360°/s²), then goes back to it.

use std::f64::consts::PI;

use super::kinematics::{JointLimits, Joints};

/// The fastest a UR5 or UR5e joint turns: 180°/s, every joint (the arms' datasheets).
pub const UR_JOINT_SPEED: f64 = PI;

/// The acceleration streamed targets are limited to by default (rad/s²): 360°/s², every
/// joint. Universal Robots publish no joint acceleration limit (UR's ROS 2 driver puts 180°/s²
/// as a placeholder); `movel` at its default speed and acceleration asks up to 3.1 rad/s² of a
/// wrist joint, which a stream of its targets must be able to follow, so twice the placeholder.
pub const UR_JOINT_ACCELERATION: f64 = 2.0 * PI;

/// Per-joint speed (rad/s) and acceleration (rad/s²) limits of a streamed target's approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoLimits {
    speed: Joints,
    acceleration: Joints,
}

impl Default for ServoLimits {
    /// [`UR_JOINT_SPEED`] and [`UR_JOINT_ACCELERATION`] on every joint.
    fn default() -> Self {
        Self {
            speed: [UR_JOINT_SPEED; 6],
            acceleration: [UR_JOINT_ACCELERATION; 6],
        }
    }
}

impl ServoLimits {
    /// Limits of `speed` (rad/s) and `acceleration` (rad/s²) per joint, base first.
    ///
    /// # Errors
    ///
    /// When a limit is not a positive number, or a speed is above [`UR_JOINT_SPEED`] (the
    /// arm's own limit), naming the joint.
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_components::robots::ur::ServoLimits;
    ///
    /// let slow = ServoLimits::new([1.0; 6], [2.0; 6])?;
    /// assert_eq!(slow.speed(), [1.0; 6]);
    /// assert!(ServoLimits::new([4.0; 6], [2.0; 6]).is_err());
    /// # Ok::<(), String>(())
    /// ```
    pub fn new(speed: Joints, acceleration: Joints) -> Result<Self, String> {
        for joint in 0..6 {
            let (v, a) = (speed[joint], acceleration[joint]);
            if !(v > 0.0 && v <= UR_JOINT_SPEED) {
                return Err(format!(
                    "joint {joint}'s speed limit {v} rad/s must be above 0 and at most the \
                     arm's {UR_JOINT_SPEED:.4} rad/s (180°/s)"
                ));
            }
            if !(a > 0.0 && a.is_finite()) {
                return Err(format!(
                    "joint {joint}'s acceleration limit {a} rad/s² must be a number above 0"
                ));
            }
        }
        Ok(Self {
            speed,
            acceleration,
        })
    }

    /// Each joint's speed limit (rad/s).
    pub fn speed(&self) -> Joints {
        self.speed
    }

    /// Each joint's acceleration limit (rad/s²).
    pub fn acceleration(&self) -> Joints {
        self.acceleration
    }
}

/// A streamed target being approached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Stream {
    target: Joints,
    /// The step the target was given at, and the step it is due by (counted in steps, so
    /// that an episode's stream is the same whatever the platform time it starts at).
    given: i64,
    due: i64,
    /// The speed the targets move at, where the arm can keep it (else 0: stop at the target).
    moving: Joints,
}

impl Stream {
    /// The stream after `target` is given at `now`, due `seconds` later, in steps of `dt`;
    /// `previous` is the stream it continues, if any.
    pub(super) fn next(
        previous: Option<&Stream>,
        target: Joints,
        now: f64,
        seconds: f64,
        dt: f64,
        limits: &ServoLimits,
    ) -> Self {
        let given = step_at(now, dt);
        let moving = match previous {
            Some(before) if given > before.given => {
                let period = (given - before.given) as f64 * dt;
                let speed: Joints =
                    std::array::from_fn(|i| (target[i] - before.target[i]) / period);
                let keepable = speed
                    .iter()
                    .zip(&limits.speed)
                    .all(|(v, most)| v.abs() <= *most);
                if keepable { speed } else { [0.0; 6] }
            }
            _ => [0.0; 6],
        };
        Self {
            target,
            given,
            due: given + step_at(seconds, dt).max(1),
            moving,
        }
    }

    /// The stream brought to a stop as fast as the limits allow from `q` at `speed`: its
    /// target becomes where each joint can stop.
    pub(super) fn stopping(&self, q: &Joints, speed: &Joints, limits: &ServoLimits) -> Self {
        let target = std::array::from_fn(|i| {
            q[i] + speed[i] * speed[i].abs() / (2.0 * limits.acceleration[i])
        });
        Self {
            target,
            given: self.given,
            due: self.given,
            moving: [0.0; 6],
        }
    }

    /// The target being approached.
    pub(super) fn target(&self) -> Joints {
        self.target
    }

    /// The setpoint a step of `dt` after `now`, from `q` moving at `speed`: its joints and
    /// their speeds over the step, within `limits` and the joints' `range`.
    pub(super) fn step(
        &self,
        q: &Joints,
        speed: &Joints,
        now: f64,
        dt: f64,
        limits: &ServoLimits,
        range: &JointLimits,
    ) -> (Joints, Joints) {
        let error: Joints = std::array::from_fn(|i| self.target[i] - q[i]);
        let now = step_at(now, dt);
        let remaining = (self.due - now).max(1) as f64 * dt;
        let held = now >= self.due;
        let wanted: Joints = std::array::from_fn(|i| error[i] / remaining);
        let fastest: Joints = std::array::from_fn(|i| {
            let along = if held {
                0.0
            } else {
                self.moving[i] * error[i].signum()
            };
            // The most from which steps of `dt`, slowing by the acceleration limit each, end
            // at the target (at the targets' own speed, while they move).
            // (√(b² + c) − b, written as c / (√(b² + c) + b): a joint a hair from its target
            // must not round to 0 and hold the others back.)
            let braking = limits.acceleration[i] * dt / 2.0;
            let reach = along.max(0.0).powi(2) + 2.0 * limits.acceleration[i] * error[i].abs();
            let stoppable = reach / ((braking.powi(2) + reach).sqrt() + braking);
            limits.speed[i].min(stoppable)
        });
        // Slowed as a whole, so that the joints keep to the line toward the target.
        let scale = fitting(&wanted, &fastest);
        let wanted: Joints = std::array::from_fn(|i| wanted[i] * scale);
        // The change of speed, too, is cut as a whole: a motion along the line stays on it.
        let change: Joints = std::array::from_fn(|i| wanted[i] - speed[i]);
        let cut = fitting(&change, &limits.acceleration.map(|a| a * dt));
        let mut next_q = *q;
        let mut next_speed = *speed;
        for i in 0..6 {
            let v = speed[i] + cut * (wanted[i] - speed[i]);
            let (lowest, highest) = range[i];
            let at = (q[i] + v * dt).clamp(lowest, highest);
            next_speed[i] = (at - q[i]) / dt;
            next_q[i] = at;
        }
        (next_q, next_speed)
    }

    /// Where the setpoint is when the target is due, stepping from `q` at `speed` at `now`.
    pub(super) fn due_from(
        &self,
        q: &Joints,
        speed: &Joints,
        now: f64,
        dt: f64,
        limits: &ServoLimits,
        range: &JointLimits,
    ) -> Joints {
        let (mut q, mut speed) = (*q, *speed);
        for step in step_at(now, dt)..self.due {
            (q, speed) = self.step(&q, &speed, step as f64 * dt, dt, limits, range);
        }
        q
    }
}

/// `to`, or the point toward it from `from` that no joint needs more than its speed limit to
/// reach in `seconds` (along the line, so that the joints stay together).
pub(super) fn within_speed(
    from: &Joints,
    to: &Joints,
    seconds: f64,
    limits: &ServoLimits,
) -> Joints {
    let far: Joints = std::array::from_fn(|i| to[i] - from[i]);
    let scale = fitting(&far, &limits.speed.map(|v| v * seconds));
    std::array::from_fn(|i| from[i] + scale * far[i])
}

/// The largest factor, at most 1, that brings every joint's `wanted` within its `most`: how a
/// motion is slowed as a whole, keeping its joints together.
fn fitting(wanted: &Joints, most: &Joints) -> f64 {
    wanted
        .iter()
        .zip(most)
        .filter(|(wanted, most)| wanted.abs() > **most)
        .map(|(wanted, most)| most / wanted.abs())
        .fold(1.0, f64::min)
}

/// The step `time` falls on, in steps of `dt`.
fn step_at(time: f64, dt: f64) -> i64 {
    (time / dt).round() as i64
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 0.002;
    const RANGE: JointLimits = [(-2.0 * PI, 2.0 * PI); 6];

    /// Streams `targets`, one every `period`, for `seconds`, from rest at 0: every step's
    /// joints and speeds.
    fn run(
        targets: impl Fn(f64) -> Joints,
        period: f64,
        seconds: f64,
    ) -> Vec<(f64, Joints, Joints)> {
        let limits = ServoLimits::default();
        let (mut q, mut speed) = ([0.0; 6], [0.0; 6]);
        let mut stream: Option<Stream> = None;
        let mut steps = Vec::new();
        let mut next_target = 0.0;
        let mut now = 0.0;
        while now < seconds {
            if now + 1e-9 >= next_target {
                stream = Some(Stream::next(
                    stream.as_ref(),
                    targets(now),
                    now,
                    period,
                    DT,
                    &limits,
                ));
                next_target += period;
            }
            let stream = stream.as_ref().unwrap();
            (q, speed) = stream.step(&q, &speed, now, DT, &limits, &RANGE);
            now += DT;
            steps.push((now, q, speed));
        }
        steps
    }

    fn assert_within_limits(steps: &[(f64, Joints, Joints)]) {
        let limits = ServoLimits::default();
        let mut before = [0.0; 6];
        for (t, _, speed) in steps {
            for i in 0..6 {
                assert!(speed[i].abs() <= limits.speed[i] + 1e-9, "t {t}: {speed:?}");
                let acceleration = (speed[i] - before[i]) / DT;
                assert!(
                    acceleration.abs() <= limits.acceleration[i] + 1e-6,
                    "t {t}: joint {i} accelerates {acceleration}"
                );
            }
            before = *speed;
        }
    }

    #[test]
    fn a_far_target_is_approached_at_the_limits_and_reached_at_rest() {
        let steps = run(|_| [3.0, -3.0, 0.5, 0.0, 0.0, 0.0], 0.05, 4.0);
        assert_within_limits(&steps);
        let (_, q, speed) = steps.last().unwrap();
        assert!(
            (q[0] - 3.0).abs() < 1e-3 && (q[1] + 3.0).abs() < 1e-3,
            "{q:?}"
        );
        assert!(speed.iter().all(|v| v.abs() < 1e-3), "{speed:?}");
        // Never past it (but for steps' rounding), and the joints keep to the line toward it.
        assert!(steps.iter().all(|(_, q, _)| q[0] <= 3.0 + 1e-5));
        let (_, halfway, _) = steps[steps.len() / 4];
        assert!(
            (halfway[2] / halfway[0] - 0.5 / 3.0).abs() < 1e-6,
            "{halfway:?}"
        );
        // At 360°/s² and 180°/s, 3 rad takes 0.5 s to reach full speed and 1.45 s in all.
        let arrived = steps.iter().position(|(_, q, _)| (q[0] - 3.0).abs() < 1e-3);
        let arrived = steps[arrived.unwrap()].0;
        assert!((1.4..1.5).contains(&arrived), "arrived at {arrived} s");
    }

    #[test]
    fn a_moving_target_the_arm_can_keep_is_followed_within_a_milliradian() {
        let path = |t: f64| [0.5 * (PI / 2.0 * t).sin(), 0.2 * t, 0.0, 0.0, 0.0, 0.0];
        let steps = run(path, 0.05, 3.0);
        assert_within_limits(&steps);
        // At each period's end the setpoint is where that period's target was.
        for (t, q, _) in &steps {
            let period_end = (t / 0.05).round() * 0.05;
            if (t - period_end).abs() < 1e-9 && *t > 1.5 {
                let target = path(period_end - 0.05);
                for i in 0..2 {
                    assert!((q[i] - target[i]).abs() < 1e-3, "t {t}: {q:?} {target:?}");
                }
            }
        }
    }

    #[test]
    fn targets_that_stop_moving_are_held_after_a_stop_within_the_limits() {
        // Targets at 1 rad/s until 1 s, then the same one for good (a policy that stalled).
        let steps = run(|t| [t.min(1.0), 0.0, 0.0, 0.0, 0.0, 0.0], 0.05, 3.0);
        assert_within_limits(&steps);
        let highest = steps.iter().map(|(_, q, _)| q[0]).fold(f64::MIN, f64::max);
        let stopping = 1.0 / (2.0 * UR_JOINT_ACCELERATION);
        assert!(highest <= 1.0 + stopping + 0.01, "overshot to {highest}");
        assert!((steps.last().unwrap().1[0] - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_target_far_ahead_of_a_moving_arm_is_never_overshot() {
        // Targets at 1 rad/s until 1 s, then one 2 rad further: out of the arm's reach in a
        // period, so reached at rest.
        let steps = run(
            |t| [if t < 1.0 { t } else { 3.0 }, 0.0, 0.0, 0.0, 0.0, 0.0],
            0.05,
            4.0,
        );
        assert_within_limits(&steps);
        assert!(steps.iter().all(|(_, q, _)| q[0] <= 3.0 + 1e-5));
        assert!((steps.last().unwrap().1[0] - 3.0).abs() < 1e-5);
    }

    #[test]
    fn stopping_ends_at_rest_within_the_acceleration_limit() {
        let limits = ServoLimits::default();
        let stream = Stream::next(None, [3.0; 6], 0.0, 0.05, DT, &limits);
        let (mut q, mut speed) = ([0.0; 6], [0.0; 6]);
        let mut now = 0.0;
        while now < 0.5 {
            (q, speed) = stream.step(&q, &speed, now, DT, &limits, &RANGE);
            now += DT;
        }
        let stopping = stream.stopping(&q, &speed, &limits);
        let before = q[0];
        for _ in 0..1000 {
            let (next_q, next_speed) = stopping.step(&q, &speed, now, DT, &limits, &RANGE);
            assert!(((next_speed[0] - speed[0]) / DT).abs() <= limits.acceleration[0] + 1e-6);
            (q, speed) = (next_q, next_speed);
            now += DT;
        }
        assert!(speed.iter().all(|v| v.abs() < 1e-6), "{speed:?}");
        // From full speed (π rad/s) at 360°/s², π/4 rad.
        assert!((q[0] - before - PI / 4.0).abs() < 0.02, "{}", q[0] - before);
    }

    #[test]
    fn a_joint_a_hair_from_its_target_does_not_hold_the_others_back() {
        let limits = ServoLimits::default();
        let q = [0.0, -1.3, 1.2, -1.5, -1.57, 3e-21];
        let stream = Stream::next(
            None,
            [2.5, -1.3, 1.2, -1.5, -1.57, 0.0],
            0.0,
            0.05,
            0.01,
            &limits,
        );
        let due = stream.due_from(&q, &[0.0; 6], 0.0, 0.01, &limits, &RANGE);
        // Five steps of 10 ms from rest at 360°/s²: a hair short of 0.01 rad.
        assert!((due[0] - 0.0094).abs() < 1e-4, "{due:?}");
    }

    #[test]
    fn limits_above_the_arm_or_not_positive_are_refused() {
        assert!(ServoLimits::new([PI; 6], [10.0; 6]).is_ok());
        let error = ServoLimits::new([PI, PI, 4.0, PI, PI, PI], [1.0; 6]).unwrap_err();
        assert!(error.contains("joint 2"), "{error}");
        assert!(ServoLimits::new([1.0; 6], [0.0; 6]).is_err());
        assert!(ServoLimits::new([f64::NAN; 6], [1.0; 6]).is_err());
    }
}
