//! What the UR and serial arms' paths (joint moves and TCP lines) share: how long a path is, how
//! far along it a length reaches, and how finely a line is checked before it starts.

use nalgebra::Isometry3;

/// The largest joint step (radians) between two checked points of a line; more means the line
/// passes a singularity or changes IK branch.
const MAX_JOINT_STEP: f64 = 0.25;

/// Spacing (metres or radians of path length) at which a line is checked before it starts.
const CHECK_SPACING: f64 = 0.005;

/// The most points a line is checked at: 500 m of line. No arm reaches so far; the bound keeps
/// a length nothing can follow (a pose 1e308 m away) from taking forever.
const MAX_CHECKED_POINTS: usize = 100_000;

/// At how many points, evenly spaced to its end, a path `length` long is checked before it
/// starts: a line's every [`CHECK_SPACING`] (at most [`MAX_CHECKED_POINTS`]); a joint move's
/// end alone (its joints move in proportion, through no singularity).
fn checked_points(length: f64, line: bool) -> usize {
    if line {
        ((length / CHECK_SPACING).ceil() as usize).clamp(1, MAX_CHECKED_POINTS)
    } else {
        1
    }
}

/// Checks, before anything moves, that an arm can follow a path `length` long (a TCP `line`,
/// or a joint move) from the joints `start`: `joints_at(along, near)` gives the joints at each
/// checked point, found near the previous point's; a line whose joints would jump more than
/// [`MAX_JOINT_STEP`] between two points (a singularity or a change of branch on the way) is
/// `singular(along, jump)`. Returns every checked point, from the start to the end: how far
/// along, and the joints there.
pub(crate) fn check<J: AsRef<[f64]>, E>(
    length: f64,
    line: bool,
    start: J,
    mut joints_at: impl FnMut(f64, &J) -> Result<J, E>,
    singular: impl Fn(f64, f64) -> E,
) -> Result<Vec<(f64, J)>, E> {
    let steps = checked_points(length, line);
    let mut points = Vec::with_capacity(steps + 1);
    points.push((0.0, start));
    for step in 1..=steps {
        let along = length * step as f64 / steps as f64;
        let (_, q) = points.last().expect("the start is a point");
        let next = joints_at(along, q)?;
        let jump = joints_length(q.as_ref(), next.as_ref());
        if line && jump > MAX_JOINT_STEP {
            return Err(singular(along, jump));
        }
        points.push((along, next));
    }
    Ok(points)
}

/// A joint move's length: the largest joint motion (radians), so that the leading joint
/// follows the profile and the others move in proportion (also the largest step between two
/// checked points).
pub(crate) fn joints_length(from: &[f64], to: &[f64]) -> f64 {
    from.iter()
        .zip(to)
        .map(|(a, b)| (b - a).abs())
        .fold(0.0, f64::max)
}

/// A TCP line's length: the longer of its distance (metres) and its turn (radians).
pub(crate) fn line_length(from: &Isometry3<f64>, to: &Isometry3<f64>) -> f64 {
    (to.translation.vector - from.translation.vector)
        .norm()
        .max(from.rotation.angle_to(&to.rotation))
}

/// The fraction (0 to 1) of a path `length` long that `along` reaches; the whole of an empty
/// path.
pub(crate) fn fraction(along: f64, length: f64) -> f64 {
    if length > 0.0 {
        (along / length).clamp(0.0, 1.0)
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Isometry3, Vector3};

    use super::*;

    #[test]
    fn the_leading_joint_or_the_longer_of_distance_and_turn_measures_a_path() {
        assert_eq!(joints_length(&[0.0, 1.0, -1.0], &[0.5, 0.0, -1.25]), 1.0);
        let from = Isometry3::identity();
        let moved = Isometry3::translation(0.3, 0.4, 0.0);
        assert!((line_length(&from, &moved) - 0.5).abs() < 1e-12);
        let turned = Isometry3::new(Vector3::new(0.1, 0.0, 0.0), Vector3::z() * 1.5);
        assert!((line_length(&from, &turned) - 1.5).abs() < 1e-12);
    }

    #[test]
    fn a_line_is_checked_every_five_millimetres_and_a_joint_move_at_its_end() {
        assert_eq!(checked_points(0.1, true), 20);
        assert_eq!(checked_points(0.0, true), 1);
        assert_eq!(checked_points(2.0, false), 1);
    }

    #[test]
    fn a_check_walks_a_line_and_stops_where_its_joints_jump() {
        let mut asked = Vec::new();
        let end = check(
            0.01,
            true,
            vec![0.0],
            |along, _| {
                asked.push(along);
                Ok::<_, (f64, f64)>(vec![along])
            },
            |along, jump| (along, jump),
        );
        assert_eq!(
            end,
            Ok(vec![
                (0.0, vec![0.0]),
                (0.005, vec![0.005]),
                (0.01, vec![0.01])
            ])
        );
        assert_eq!(asked, [0.005, 0.01]);
        let jumping = |along: f64, _: &Vec<f64>| Ok(vec![if along > 0.006 { 1.0 } else { 0.0 }]);
        assert_eq!(
            check(0.01, true, vec![0.0], jumping, |along, jump| (along, jump)),
            Err((0.01, 1.0))
        );
        assert_eq!(
            check(0.01, false, vec![0.0], jumping, |along, jump| (along, jump))
                .map(|points| points.last().cloned()),
            Ok(Some((0.01, vec![1.0])))
        );
    }

    #[test]
    fn a_fraction_stays_on_the_path_and_an_empty_path_is_done() {
        assert_eq!(fraction(0.25, 1.0), 0.25);
        assert_eq!(fraction(-1.0, 2.0), 0.0);
        assert_eq!(fraction(3.0, 2.0), 1.0);
        assert_eq!(fraction(0.0, 0.0), 1.0);
    }
}
