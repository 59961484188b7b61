//! [`GripperParts`]: a two-finger gripper named by its servos and pads alone, and the
//! measuring that finds the rest — each servo's open and closed controls, the opening over the
//! stroke, how fast the fingers move, how close the servos get — by sweeping the stroke in a
//! copy of the model where only the gripper's own parts collide, the rest of the world held
//! where it starts.

use std::borrow::Cow;
use std::sync::{Arc, Mutex, PoisonError, Weak};

use yarok_core::component::{Bind, BindError};
use yarok_mjc::{ActuatorId, BodyId, Data, JointId, Model, ServoGains, Sim, SimBind};

use super::REACHED_COUNTS;
use super::names::{FingerServo, Stroke};
use super::sim::{check_servos_and_pads, position_servo};

/// The parts of a two-finger gripper: the position servos that close it and its pads' bodies
/// `[left, right]` (and the sites on the pads' faces, if it has them). yarok measures the rest
/// when it binds ([`ParallelGripper::bind_sim_measured`](super::ParallelGripper::bind_sim_measured)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GripperParts {
    /// The servos closing the fingers: every actuator of the gripper, each a position servo
    /// with a limited control range.
    pub servos: &'static [&'static str],
    /// The pads' bodies.
    pub pads: [&'static str; 2],
    /// Sites on the pads' faces.
    pub pad_sites: Option<[&'static str; 2]>,
}

/// What measuring a gripper found.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Measured {
    pub(super) servos: Vec<FingerServo>,
    /// Each servo's length where it settles at its open and closed controls.
    pub(super) lengths: Vec<[f64; 2]>,
    pub(super) stroke: Stroke,
    pub(super) reached: f64,
}

/// How many steps of the control range the stroke is swept in.
const SWEEP_STEPS: usize = 24;

/// How many openings the measured table holds.
const TABLE_POINTS: usize = 9;

/// The least change of the gap (metres) that counts as a servo moving a pad.
const MOVES_A_PAD: f64 = 2e-4;

/// The shortest stroke (metres) a gripper may have: less is a file misread (its radians taken
/// for degrees) or a mapping of the wrong servos.
const SHORTEST_STROKE: f64 = 5e-3;

/// How many times its joint's range a servo's control range may be before the file counts as
/// misread (a control range in radians over a joint range read in degrees is 57 times it).
const MISREAD_RATIO: f64 = 10.0;

/// What to check when the fingers barely move.
const BARELY_MOVING: &str = "a file in radians that does not say so (no <compiler \
    angle=\"radian\"/>) is read in degrees, its joints barely moving: state its unit (README, \
    \"Arms of any make\")";

/// Seconds a servo is given to settle at each control.
const SETTLE_SECONDS: f64 = 3.0;

/// The ratio of the 2F-85's slowest to fastest speed, kept for a measured gripper.
const SLOWEST_SHARE: f64 = 20.0 / 150.0;

/// The most a measured gripper's fastest speed is taken to be (mm/s), as the 2F-85's.
const FASTEST_MM_S: f64 = 150.0;

struct SweptServo {
    name: &'static str,
    id: ActuatorId,
    gains: ServoGains,
    range: [f64; 2],
}

impl SweptServo {
    /// The control at `fraction` of the way from `from` to `to`.
    fn control(from: f64, to: f64, fraction: f64) -> f64 {
        from + (to - from) * fraction
    }
}

/// A copy of the model where the gripper is swept, the pads its gap is measured between, and
/// the joints of the rest of the world, held where they start (the gripper hangs as it is
/// mounted, under gravity).
struct Bench {
    data: Data,
    servos: Vec<SweptServo>,
    pads: [BodyId; 2],
    held: Vec<(JointId, Vec<f64>)>,
}

impl Bench {
    /// The gap between the pads' surfaces (metres; negative where they overlap).
    fn gap(&mut self) -> f64 {
        let [left, right] = self.pads;
        self.data
            .body_gap(left, right)
            .expect("checked when the bench was made: both pads have colliding geoms")
    }

    /// Sets each servo's control and steps until they are still (or [`SETTLE_SECONDS`] pass);
    /// the seconds taken.
    fn settle(&mut self, controls: &[f64]) -> f64 {
        for (servo, &control) in self.servos.iter().zip(controls) {
            self.data.set_ctrl(servo.id, control);
        }
        let timestep = self.data.model().timestep();
        let steps = (SETTLE_SECONDS / timestep) as usize;
        let mut still = 0;
        for step in 0..steps {
            self.data.step();
            for (joint, position) in &self.held {
                self.data.qpos_mut(*joint).copy_from_slice(position);
                self.data.qvel_mut(*joint).fill(0.0);
            }
            let moving = self.servos.iter().any(|servo| {
                let (length, rate) = self.data.actuator_length(servo.id);
                let span = (servo.range[1] - servo.range[0]).abs() * servo.gains.gain
                    / servo.gains.kp.max(f64::MIN_POSITIVE);
                rate.abs() > 1e-3 * span.max(1e-9) || !length.is_finite()
            });
            still = if moving { 0 } else { still + 1 };
            if still >= 10 {
                return step as f64 * timestep;
            }
        }
        SETTLE_SECONDS
    }

    /// Each servo's length where it stands.
    fn lengths(&self) -> Vec<f64> {
        self.servos
            .iter()
            .map(|servo| self.data.actuator_length(servo.id).0)
            .collect()
    }
}

/// What was measured of each gripper in each live model (worlds compiled from the same
/// composition share one model): the model, the gripper's path and parts, what was found.
type Measurements = Vec<(Weak<Model>, String, Measured)>;

static MEASURED: Mutex<Measurements> = Mutex::new(Vec::new());

/// Measures the gripper `parts` names (once per model: later binds in worlds sharing the model
/// reuse it).
pub(super) fn measure(bind: &Bind<Sim>, parts: &GripperParts) -> Result<Measured, BindError> {
    let model = Arc::clone(bind.backend().model());
    let key = format!("{} {parts:?}", bind.path());
    let found = |measured: &Measurements| {
        measured
            .iter()
            .find(|(of, at, _)| *at == key && of.upgrade().is_some_and(|m| Arc::ptr_eq(&m, &model)))
            .map(|(_, _, measured)| measured.clone())
    };
    if let Some(measured) = found(&MEASURED.lock().unwrap_or_else(PoisonError::into_inner)) {
        return Ok(measured);
    }
    let measured = sweep_anew(bind, parts, &model)?;
    let mut cache = MEASURED.lock().unwrap_or_else(PoisonError::into_inner);
    cache.retain(|(of, _, _)| of.strong_count() > 0);
    cache.push((Arc::downgrade(&model), key, measured.clone()));
    Ok(measured)
}

/// Refuses a mapping that leaves out an actuator of the gripper (a third finger) or names a
/// servo that moves neither pad, then sweeps the stroke.
fn sweep_anew(
    bind: &Bind<Sim>,
    parts: &GripperParts,
    model: &Arc<Model>,
) -> Result<Measured, BindError> {
    check_servos_and_pads(bind, parts.servos.len(), parts.pads)?;
    let mut servos = Vec::with_capacity(parts.servos.len());
    for &name in parts.servos {
        let (actuator, gains) = position_servo(bind, name)?;
        let range = actuator.ctrl_range().ok_or_else(|| {
            bind.error(format!(
                "actuator {name:?} has no control range (ctrlrange): the stroke is measured \
                 over it"
            ))
        })?;
        servos.push(SweptServo {
            name,
            id: actuator.id(),
            gains,
            range,
        });
    }
    refuse_unnamed_actuators(bind, model, &servos)?;
    for servo in &servos {
        let (name, range) = (servo.name, servo.range);
        if let Some(joint) = model.actuator_joint(servo.id)
            && let Some([lowest, highest]) = model.joint_range(joint)
        {
            let reach = (highest - lowest).abs() * servo.gains.gear.abs();
            let asked = (range[1] - range[0]).abs();
            if asked > MISREAD_RATIO * reach {
                let joint = model.joint_name(joint).unwrap_or_default();
                return Err(bind.error(format!(
                    "servo {name:?}: its control range [{}, {}] is {:.0} times its joint \
                     {joint:?}'s range [{lowest:.4}, {highest:.4}]: {BARELY_MOVING}",
                    range[0],
                    range[1],
                    asked / reach
                )));
            }
        }
    }
    let pads = [
        bind.body(parts.pads[0])?.id(),
        bind.body(parts.pads[1])?.id(),
    ];
    let prefix = component_prefix(bind);
    let own_bodies: Vec<BodyId> = model
        .bodies()
        .filter(|&body| {
            model
                .body_name(body)
                .is_some_and(|name| name.starts_with(&prefix))
        })
        .collect();
    let study = model
        .colliding_only(&own_bodies)
        .map_err(|e| bind.error(e.to_string()))?;
    let mut data = Data::new(&Arc::new(study)).map_err(|e| bind.error(e.to_string()))?;
    let held = model
        .joints()
        .filter(|&joint| {
            model
                .joint_name(joint)
                .is_none_or(|name| !name.starts_with(&prefix))
        })
        .map(|joint| (joint, data.qpos(joint).to_vec()))
        .collect();
    data.forward();
    if data.body_gap(pads[0], pads[1]).is_none() {
        return Err(bind.error(format!(
            "pads {:?} and {:?}: the opening is measured between their colliding geoms, and \
             one has none",
            parts.pads[0], parts.pads[1]
        )));
    }
    let mut bench = Bench {
        data,
        servos,
        pads,
        held,
    };
    sweep(bind, &mut bench)
}

/// What the names of the component's own parts start with in the composed model.
fn component_prefix(bind: &Bind<Sim>) -> String {
    match bind.path().trim_start_matches('/') {
        "" => String::new(),
        path => format!("{path}/"),
    }
}

/// Refuses a mapping that leaves out one of the gripper's own actuators: a finger it would
/// leave undriven (the Jaco hand's third).
fn refuse_unnamed_actuators(
    bind: &Bind<Sim>,
    model: &Model,
    servos: &[SweptServo],
) -> Result<(), BindError> {
    let prefix = component_prefix(bind);
    let unnamed: Vec<String> = model
        .actuators()
        .filter(|&actuator| servos.iter().all(|servo| servo.id != actuator))
        .filter_map(|actuator| model.actuator_name(actuator))
        .filter_map(|name| name.strip_prefix(&prefix).map(str::to_owned))
        .filter(|name| !name.contains('/'))
        .collect();
    if unnamed.is_empty() {
        return Ok(());
    }
    Err(bind.error(format!(
        "the gripper has actuators the mapping leaves out ({}): a parallel gripper drives two \
         fingers with every servo it has named; a hand with more fingers is not one",
        unnamed.join(", ")
    )))
}

/// Finds each servo's open end, sweeps the stroke from open to the other end, and reads off
/// where the pads meet, the openings between, the speed and how close the servos get.
fn sweep(bind: &Bind<Sim>, bench: &mut Bench) -> Result<Measured, BindError> {
    let middles: Vec<f64> = bench
        .servos
        .iter()
        .map(|servo| (servo.range[0] + servo.range[1]) / 2.0)
        .collect();
    let mut open = Vec::with_capacity(middles.len());
    let mut closed = Vec::with_capacity(middles.len());
    for i in 0..bench.servos.len() {
        let [lowest, highest] = bench.servos[i].range;
        let mut controls = middles.clone();
        controls[i] = lowest;
        bench.settle(&controls);
        let at_lowest = bench.gap();
        controls[i] = highest;
        bench.settle(&controls);
        let at_highest = bench.gap();
        if (at_highest - at_lowest).abs() < MOVES_A_PAD {
            return Err(bind.error(format!(
                "servo {:?} moves neither pad: over its whole control range [{lowest}, \
                 {highest}] the gap between the pads changes by {:.2} mm. A finger the pads are \
                 not on (a hand of more than two fingers) is not a parallel gripper's; \
                 {BARELY_MOVING}",
                bench.servos[i].name,
                (at_highest - at_lowest).abs() * 1e3
            )));
        }
        let (wide, narrow) = if at_highest > at_lowest {
            (highest, lowest)
        } else {
            (lowest, highest)
        };
        open.push(wide);
        closed.push(narrow);
    }
    bench.settle(&open);
    let wide = bench.gap();
    let seconds = bench.settle(&closed);
    let narrow = bench.gap();
    let mut samples = Vec::with_capacity(SWEEP_STEPS + 1);
    for step in 0..=SWEEP_STEPS {
        let fraction = step as f64 / SWEEP_STEPS as f64;
        let controls: Vec<f64> = (0..open.len())
            .map(|i| SweptServo::control(open[i], closed[i], fraction))
            .collect();
        bench.settle(&controls);
        samples.push((fraction, bench.gap(), bench.lengths()));
    }
    // The stroke's ends: the last control at which the fingers are still fully open, and the
    // first at which the pads meet, or else the fingers stop closing (a joint at its limit).
    let narrowest = samples
        .iter()
        .map(|(_, gap, _)| *gap)
        .fold(f64::INFINITY, f64::min);
    let meeting = samples
        .windows(2)
        .find(|pair| pair[1].1 <= 0.0)
        .map(|pair| {
            let ((f0, g0, _), (f1, g1, _)) = (&pair[0], &pair[1]);
            f0 + (f1 - f0) * g0 / (g0 - g1)
        })
        .or_else(|| {
            samples
                .iter()
                .find(|(_, gap, _)| *gap <= narrowest + MOVES_A_PAD)
                .map(|(fraction, _, _)| *fraction)
        })
        .unwrap_or(1.0);
    let widest = samples
        .iter()
        .map(|(_, gap, _)| *gap)
        .fold(f64::NEG_INFINITY, f64::max);
    if widest - narrowest < SHORTEST_STROKE {
        return Err(bind.error(format!(
            "the pads open only {:.1} mm over the servos' whole control ranges ({:.1} to \
             {:.1} mm between them): {BARELY_MOVING}",
            (widest - narrowest) * 1e3,
            widest * 1e3,
            narrowest * 1e3
        )));
    }
    let opening = samples
        .iter()
        .rev()
        .find(|(fraction, gap, _)| *fraction < meeting && *gap >= widest - MOVES_A_PAD)
        .map_or(0.0, |(fraction, _, _)| *fraction);
    let (open, closed): (Vec<f64>, Vec<f64>) = (0..open.len())
        .map(|i| {
            (
                SweptServo::control(open[i], closed[i], opening),
                SweptServo::control(open[i], closed[i], meeting),
            )
        })
        .unzip();
    let (opening, meeting) = (opening, meeting - opening);
    // The stroke's ends: where each servo settles at its open and meeting controls.
    bench.settle(&open);
    let open_lengths = bench.lengths();
    bench.settle(&closed);
    let closed_lengths = bench.lengths();
    let lengths: Vec<[f64; 2]> = open_lengths
        .iter()
        .zip(&closed_lengths)
        .map(|(&open, &closed)| [open, closed])
        .collect();
    // Each sample within the stroke: the position commanded, the servos' mean position
    // (0–255 between their settled ends), the gap.
    let within: Vec<(f64, f64, f64)> = samples
        .iter()
        .map(|(fraction, gap, at)| (fraction - opening, gap, at))
        .filter(|(fraction, _, _)| (0.0..=meeting).contains(fraction))
        .map(|(fraction, gap, at)| {
            let position = at
                .iter()
                .zip(&lengths)
                .map(|(at, [open, closed])| 255.0 * (at - open) / (closed - open))
                .sum::<f64>()
                / at.len() as f64;
            (fraction / meeting * 255.0, position, *gap)
        })
        .collect();
    let short = within
        .iter()
        .map(|(commanded, position, _)| (commanded - position).abs())
        .fold(0.0, f64::max);
    let mut by_position: Vec<(f64, f64)> = within
        .iter()
        .map(|&(_, position, gap)| (position.clamp(0.0, 255.0), gap))
        .chain([(255.0, bench.gap())])
        .collect();
    by_position.sort_by(|a, b| a.0.total_cmp(&b.0));
    let gap_at = |position: f64| -> f64 {
        let i = by_position
            .windows(2)
            .position(|pair| position <= pair[1].0)
            .unwrap_or(by_position.len() - 2);
        let ((p0, g0), (p1, g1)) = (by_position[i], by_position[i + 1]);
        if p1 > p0 {
            g0 + (g1 - g0) * (position - p0) / (p1 - p0)
        } else {
            g1
        }
    };
    let mut opening_mm: Vec<f64> = Vec::with_capacity(TABLE_POINTS);
    for k in 0..TABLE_POINTS {
        let gap = gap_at(255.0 * k as f64 / (TABLE_POINTS - 1) as f64).max(0.0) * 1e3;
        let narrower = opening_mm.last().map_or(gap, |&last| gap.min(last));
        opening_mm.push(narrower);
    }
    let travelled_mm = (wide - narrow).max(0.0) * 1e3;
    let fastest = (0.8 * travelled_mm / seconds.max(1e-3)).min(FASTEST_MM_S);
    let servos = bench
        .servos
        .iter()
        .enumerate()
        .map(|(i, servo)| FingerServo {
            actuator: servo.name,
            open: open[i],
            closed: closed[i],
        })
        .collect();
    Ok(Measured {
        servos,
        lengths,
        stroke: Stroke {
            opening_mm: Cow::Owned(opening_mm),
            speed_mm_s: [fastest * SLOWEST_SHARE, fastest],
        },
        reached: (1.5 * short + 1.0).max(REACHED_COUNTS),
    })
}
