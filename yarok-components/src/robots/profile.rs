//! [`Profile`]: how far along a path an arm's motion is at each moment — a trapezoidal speed
//! profile from rest to rest, as the UR controller's `movej` and `movel` use, or a stop.

/// Piecewise-constant acceleration from a start position and speed along a path: at most three
/// phases (accelerate, cruise, decelerate), after which it rests.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Profile {
    start: f64,
    speed: f64,
    /// `(duration, acceleration)` of each phase.
    phases: [(f64, f64); 3],
}

impl Profile {
    /// From rest at 0 to rest at `length`, never faster than `speed` nor accelerating harder
    /// than `acceleration` (both positive): a trapezoid, or a triangle when the path is too
    /// short to reach `speed`.
    pub(crate) fn rest_to_rest(length: f64, speed: f64, acceleration: f64) -> Self {
        let ramp = speed / acceleration;
        let (ramp, cruise) = if length >= speed * ramp {
            (ramp, length / speed - ramp)
        } else {
            ((length / acceleration).sqrt(), 0.0)
        };
        Self {
            start: 0.0,
            speed: 0.0,
            phases: [(ramp, acceleration), (cruise, 0.0), (ramp, -acceleration)],
        }
    }

    /// From `position` at `speed` (≥ 0) to rest, decelerating at `deceleration`.
    pub(crate) fn stopping(position: f64, speed: f64, deceleration: f64) -> Self {
        Self {
            start: position,
            speed,
            phases: [
                (speed / deceleration, -deceleration),
                (0.0, 0.0),
                (0.0, 0.0),
            ],
        }
    }

    /// The acceleration it starts with (its deceleration, for a stop), as a positive number.
    pub(crate) fn acceleration(&self) -> f64 {
        self.phases[0].1.abs()
    }

    /// Seconds until it rests.
    pub(crate) fn duration(&self) -> f64 {
        self.phases.iter().map(|(duration, _)| duration).sum()
    }

    /// Position and speed `t` seconds after the start (at rest before 0 and after the end).
    pub(crate) fn at(&self, t: f64) -> (f64, f64) {
        let (mut position, mut speed) = (self.start, self.speed);
        let mut left = t.max(0.0);
        for (duration, acceleration) in self.phases {
            let dt = left.min(duration);
            position += speed * dt + 0.5 * acceleration * dt * dt;
            speed += acceleration * dt;
            left -= dt;
        }
        if left > 0.0 {
            speed = 0.0;
        }
        (position, speed.max(0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::Profile;

    #[test]
    fn a_long_path_cruises_at_the_speed_and_ends_at_rest_on_its_length() {
        let profile = Profile::rest_to_rest(1.0, 0.25, 1.2);
        let ramp = 0.25 / 1.2;
        assert!((profile.duration() - (1.0 / 0.25 + ramp)).abs() < 1e-12);
        assert_eq!(profile.at(profile.duration() / 2.0).1, 0.25);
        let (end, speed) = profile.at(profile.duration() + 1.0);
        assert!((end - 1.0).abs() < 1e-12 && speed == 0.0);
    }

    #[test]
    fn a_short_path_is_a_triangle_that_never_exceeds_its_limits() {
        let profile = Profile::rest_to_rest(0.01, 0.25, 1.2);
        let steps = 1000;
        let dt = profile.duration() / steps as f64;
        let mut last = profile.at(0.0);
        for i in 1..=steps {
            let now = profile.at(i as f64 * dt);
            assert!(now.1 <= 0.25 + 1e-12);
            assert!((now.1 - last.1).abs() / dt <= 1.2 + 1e-9);
            last = now;
        }
        assert!((last.0 - 0.01).abs() < 1e-12);
    }

    #[test]
    fn stopping_decelerates_to_rest() {
        let profile = Profile::stopping(0.3, 0.5, 2.0);
        assert!((profile.duration() - 0.25).abs() < 1e-12);
        let (end, speed) = profile.at(1.0);
        assert!((end - (0.3 + 0.5 * 0.25 / 2.0)).abs() < 1e-12 && speed == 0.0);
    }
}
