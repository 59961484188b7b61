//! [`GripperNames`]: which servos of a model close a parallel gripper, where its pads are, and
//! its stroke.

use std::borrow::Cow;

/// One position servo of a gripper and its controls at the two ends of the stroke.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FingerServo {
    /// The actuator: a position servo on a joint or a tendon.
    pub actuator: &'static str,
    /// Its control with the fingers fully open (position 0).
    pub open: f64,
    /// Its control with the pads meeting (position 255).
    pub closed: f64,
}

/// A gripper's opening over its stroke and how fast its fingers move.
#[derive(Debug, Clone, PartialEq)]
pub struct Stroke {
    /// The opening between the pad faces (millimetres) at evenly spaced positions from 0
    /// (open) to 255 (closed): at least two, widest first.
    pub opening_mm: Cow<'static, [f64]>,
    /// The speed of the opening (mm/s) at speed requests 0 and 255.
    pub speed_mm_s: [f64; 2],
}

impl Stroke {
    /// The Robotiq 2F-85's: its linkage's table (driver angles 0, 0.2, 0.4, 0.6 and 0.8 rad,
    /// as yarok's and Menagerie's models close) at 20 to 150 mm/s.
    pub const ROBOTIQ_2F85: Self = Self {
        opening_mm: Cow::Borrowed(&[85.4, 66.6, 45.6, 23.1, 0.2]),
        speed_mm_s: [20.0, 150.0],
    };

    /// MuJoCo Menagerie's 2F-85 model's: its pad faces' gap measured at controls 0, 62.25,
    /// 124.5, 186.75 and 249 (where they meet), at the real gripper's 20 to 150 mm/s.
    pub const MENAGERIE_2F85: Self = Self {
        opening_mm: Cow::Borrowed(&[85.2, 66.0, 44.8, 22.2, 0.0]),
        speed_mm_s: [20.0, 150.0],
    };

    /// The Franka hand's: 79 mm between robosuite's pad faces when open, closing evenly, at the
    /// real hand's 0.05 m/s per finger at most.
    pub const FRANKA_HAND: Self = Self {
        opening_mm: Cow::Borrowed(&[79.0, 0.0]),
        speed_mm_s: [10.0, 100.0],
    };

    /// The widest opening less the narrowest (millimetres).
    pub fn length_mm(&self) -> f64 {
        self.opening_mm[0] - self.opening_mm[self.opening_mm.len() - 1]
    }

    /// The opening (millimetres) at `position` (0 to 255), by the table.
    pub fn opening_at(&self, position: f64) -> f64 {
        let segments = self.opening_mm.len() - 1;
        let at = (position / 255.0 * segments as f64).clamp(0.0, segments as f64);
        let segment = (at.floor() as usize).min(segments - 1);
        let (wide, narrow) = (self.opening_mm[segment], self.opening_mm[segment + 1]);
        wide + (narrow - wide) * (at - segment as f64)
    }

    /// The position (0 to 255) at an opening of `millimetres`, by the table.
    pub fn position_for(&self, millimetres: f64) -> u8 {
        let table = &self.opening_mm;
        let segments = table.len() - 1;
        let gap = millimetres.clamp(table[segments], table[0]);
        let segment = table
            .windows(2)
            .position(|pair| gap >= pair[1])
            .unwrap_or(segments - 1);
        let (wide, narrow) = (table[segment], table[segment + 1]);
        let at = segment as f64 + (wide - gap) / (wide - narrow);
        (at / segments as f64 * 255.0).round().clamp(0.0, 255.0) as u8
    }

    /// How many positions a second the fingers cover at a speed request (0 to 255).
    pub fn positions_per_second(&self, speed: f64) -> f64 {
        let [slowest, fastest] = self.speed_mm_s;
        (slowest + (fastest - slowest) * speed / 255.0) * 255.0 / self.length_mm()
    }
}

/// The names of a parallel gripper's parts in its model: the position servos that close it
/// (one, or one per finger), the pads' bodies `[left, right]` and the sites on their faces if
/// it has them; and its stroke. Mappings for the common files are constants.
#[derive(Debug, Clone, PartialEq)]
pub struct GripperNames {
    /// The servos closing the fingers, all driven to the same position.
    pub servos: &'static [FingerServo],
    /// The pads' bodies.
    pub pads: [&'static str; 2],
    /// Sites on the pads' faces.
    pub pad_sites: Option<[&'static str; 2]>,
    /// The opening over the stroke, and the speeds.
    pub stroke: Stroke,
    /// How many positions short of a request the fingers may stop and count as there (not
    /// on an object): [`REACHED_COUNTS`](super::REACHED_COUNTS), or more where the joints'
    /// friction holds the servos back.
    pub reached: f64,
}

impl GripperNames {
    /// yarok's own 2F-85 template ([`Robotiq2f85`](crate::grippers::Robotiq2f85)).
    pub const YAROK_2F85: Self = Self {
        servos: &[FingerServo {
            actuator: "fingers",
            open: 0.0,
            closed: 255.0,
        }],
        pads: ["left_pad", "right_pad"],
        pad_sites: Some(["left_pad", "right_pad"]),
        stroke: Stroke::ROBOTIQ_2F85,
        reached: super::REACHED_COUNTS,
    };

    /// MuJoCo Menagerie's `robotiq_2f85/2f85.xml`: its pads meet at control 249 of 255.
    pub const MENAGERIE_2F85: Self = Self {
        servos: &[FingerServo {
            actuator: "fingers_actuator",
            open: 0.0,
            closed: 249.0,
        }],
        pads: ["left_pad", "right_pad"],
        pad_sites: None,
        stroke: Stroke::MENAGERIE_2F85,
        reached: super::REACHED_COUNTS,
    };

    /// robosuite's Franka hand (`grippers/panda_gripper.xml`): one servo per finger, the pads
    /// meeting at 0.5 mm of each finger's travel. Each finger's 1 N of friction holds its
    /// 1000 N/m servo up to 1 mm (6.4 positions) short, so a request counts as reached within
    /// 8 positions (2.5 mm of opening), as the real hand's grasp counts a width within its
    /// tolerance.
    pub const ROBOSUITE_PANDA: Self = Self {
        servos: &[
            FingerServo {
                actuator: "gripper_finger_joint1",
                open: 0.04,
                closed: 0.0005,
            },
            FingerServo {
                actuator: "gripper_finger_joint2",
                open: -0.04,
                closed: -0.0005,
            },
        ],
        pads: ["finger_joint1_tip", "finger_joint2_tip"],
        pad_sites: None,
        stroke: Stroke::FRANKA_HAND,
        reached: 8.0,
    };
}

#[cfg(test)]
mod tests {
    use super::Stroke;

    #[test]
    fn openings_and_positions_follow_the_table() {
        let stroke = Stroke::ROBOTIQ_2F85;
        assert_eq!(stroke.position_for(85.4), 0);
        assert_eq!(stroke.position_for(0.2), 255);
        assert_eq!(stroke.position_for(45.6), 128);
        assert_eq!(stroke.position_for(1000.0), 0);
        assert!((stroke.opening_at(127.5) - 45.6).abs() < 1e-9);
        assert!((stroke.opening_at(31.875) - 76.0).abs() < 1e-9);
        let hand = Stroke::FRANKA_HAND;
        assert_eq!(hand.position_for(39.5), 128);
        assert!((hand.opening_at(255.0)).abs() < 1e-9);
    }
}
