//! URScript for the arm's motions, as the controller receives it: pure functions from numbers
//! to text, sent over the secondary interface
//! ([`send_script`](super::secondary::send_script)).
//!
//! Joint angles and pose vectors are written with six decimals (a micro-radian, a micrometre);
//! speeds, accelerations, masses and centres of mass as Rust writes an `f64`, the shortest text
//! that reads back to the same number (`1.4`, `2`, `0.05`); a stop's deceleration the same way
//! but always with a decimal point (`stopj(2.0)`), as the UR manual writes it. Callers pass finite numbers: the
//! arm's interface checks its targets and limits before it builds a script.
//!
//! ```
//! use yarok_hw::ur::script;
//!
//! assert_eq!(
//!     script::movej(&[0.3, -1.5, 1.4, -1.2, -1.6, 0.0], 1.05, 1.4),
//!     "movej([0.300000, -1.500000, 1.400000, -1.200000, -1.600000, 0.000000], a=1.4, v=1.05)"
//! );
//! ```

/// A pose vector `p[x, y, z, rx, ry, rz]` (metres, and an axis-angle rotation in radians).
pub fn pose(values: &[f64; 6]) -> String {
    format!("p{}", six_decimals(values))
}

/// `[a, b, …]` with six decimals each.
fn six_decimals(values: &[f64]) -> String {
    let values: Vec<String> = values.iter().map(|value| format!("{value:.6}")).collect();
    format!("[{}]", values.join(", "))
}

/// `movej` to the joint angles `q` (radians) at `speed` rad/s and `acceleration` rad/s².
pub fn movej(q: &[f64; 6], speed: f64, acceleration: f64) -> String {
    format!("movej({}, a={acceleration}, v={speed})", six_decimals(q))
}

/// `servoj` to the joint angles `q` (radians), reached in `seconds` (the control period of
/// whoever streams them), smoothed over `lookahead` seconds with `gain` (URScript's range
/// 0.03–0.2 s and 100–2000): the command a policy streams at its rate.
///
/// ```
/// use yarok_hw::ur::script;
///
/// assert_eq!(
///     script::servoj(&[0.3, -1.5, 1.4, -1.2, -1.6, 0.0], 0.05, 0.1, 300.0),
///     "servoj([0.300000, -1.500000, 1.400000, -1.200000, -1.600000, 0.000000], t=0.05, lookahead_time=0.1, gain=300)"
/// );
/// ```
pub fn servoj(q: &[f64; 6], seconds: f64, lookahead: f64, gain: f64) -> String {
    format!(
        "servoj({}, t={seconds}, lookahead_time={lookahead}, gain={gain})",
        six_decimals(q)
    )
}

/// A program that sets the TCP (`tcp`, a pose in the flange frame) and runs `movel` to the TCP
/// pose `to` (in the base frame) at `speed` m/s and `acceleration` m/s². A program, so that the
/// TCP it moves by is the one it was planned with.
pub fn movel_with_tcp(to: &[f64; 6], tcp: &[f64; 6], speed: f64, acceleration: f64) -> String {
    format!(
        "def yarok_move():\n  set_tcp({})\n  movel({}, a={acceleration}, v={speed})\nend",
        pose(tcp),
        pose(to)
    )
}

/// `stopj`: joint motion stops, decelerating at `deceleration` rad/s².
pub fn stopj(deceleration: f64) -> String {
    format!("stopj({})", with_decimal_point(deceleration))
}

/// `stopl`: linear motion stops, decelerating at `deceleration` m/s².
pub fn stopl(deceleration: f64) -> String {
    format!("stopl({})", with_decimal_point(deceleration))
}

/// The shortest text of `value`, with `.0` after a whole number.
fn with_decimal_point(value: f64) -> String {
    let text = value.to_string();
    if text.contains('.') {
        text
    } else {
        text + ".0"
    }
}

/// `set_payload`: the arm carries `mass` kilograms centred at `centre` (metres, flange frame).
pub fn set_payload(mass: f64, centre: [f64; 3]) -> String {
    let [x, y, z] = centre;
    format!("set_payload({mass}, [{x}, {y}, {z}])")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joints_and_poses_have_six_decimals_rounded_and_signed() {
        assert_eq!(
            movej(
                &[
                    0.1234566,
                    -2.0,
                    1e-9,
                    -1e-9,
                    3.0000004,
                    std::f64::consts::TAU
                ],
                0.5,
                1.4
            ),
            "movej([0.123457, -2.000000, 0.000000, -0.000000, 3.000000, 6.283185], a=1.4, v=0.5)"
        );
        assert_eq!(
            pose(&[0.4, -0.25, 0.1, std::f64::consts::PI, 0.0, -0.0]),
            "p[0.400000, -0.250000, 0.100000, 3.141593, 0.000000, -0.000000]"
        );
    }

    #[test]
    fn a_line_is_a_program_that_sets_its_tcp_first() {
        assert_eq!(
            movel_with_tcp(
                &[0.5, 0.1, 0.2, 3.0, 0.0, 0.0],
                &[0.0, 0.0, 0.1558, 0.0, 0.0, 0.0],
                0.25,
                1.2
            ),
            "def yarok_move():\n\
             \x20 set_tcp(p[0.000000, 0.000000, 0.155800, 0.000000, 0.000000, 0.000000])\n\
             \x20 movel(p[0.500000, 0.100000, 0.200000, 3.000000, 0.000000, 0.000000], a=1.2, v=0.25)\n\
             end"
        );
    }

    #[test]
    fn speeds_masses_and_stops_are_the_shortest_text_of_their_number() {
        assert_eq!(stopj(2.0), "stopj(2.0)");
        assert_eq!(stopl(4.0), "stopl(4.0)");
        assert_eq!(stopl(0.1 + 0.2), "stopl(0.30000000000000004)");
        assert_eq!(stopj(1e-7), "stopj(0.0000001)");
        assert_eq!(
            set_payload(1.2, [0.0, -0.01, 0.05]),
            "set_payload(1.2, [0, -0.01, 0.05])"
        );
        assert_eq!(
            movej(&[0.0; 6], 3.0, 1e3).split(", a=").nth(1),
            Some("1000, v=3)")
        );
    }
}
