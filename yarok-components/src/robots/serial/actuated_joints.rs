//! [`ActuatedJoints`]: each joint of a serial arm in `sim` — its actuator, what the joint
//! resists with by itself, and the most force the actuator can give it — found from a mapping
//! ([`SerialNames`]) and checked against the model before anything moves.

use yarok_core::component::{Bind, BindError};
use yarok_mjc::{Actuator, Joint, JointLosses, Model, ServoGains, Sim, SimBind};

use super::names::SerialNames;

/// How an actuator moves its joint.
#[derive(Debug, Clone, Copy)]
pub(super) enum Actuation {
    /// A torque motor: force = gear × control.
    Motor { gear: f64 },
    /// A position servo.
    Servo(ServoGains),
}

/// One joint of the arm and what drives it.
pub(super) struct ActuatedJoint {
    pub(super) name: String,
    pub(super) joint: Joint,
    pub(super) actuator: Actuator,
    pub(super) actuation: Actuation,
    pub(super) losses: JointLosses,
    /// The least and most force (N·m, or N for a slide) the actuator can put on the joint.
    pub(super) force_range: [f64; 2],
}

impl ActuatedJoint {
    /// The most force the actuator gives either way.
    pub(super) fn strength(&self) -> f64 {
        self.force_range[0].abs().min(self.force_range[1].abs())
    }
}

/// The arm's joints base to tip, each with its drive.
pub(super) type ActuatedJoints = Vec<ActuatedJoint>;

/// The drives `names` maps, each checked: the joint exists and is a hinge or slide, its actuator
/// is a torque motor or a position servo on that very joint, no joint or actuator is named
/// twice.
pub(super) fn actuated_joints(
    bind: &mut Bind<Sim>,
    names: &SerialNames,
) -> Result<ActuatedJoints, BindError> {
    let by_joint = names.actuators.is_empty();
    if (!by_joint && names.joints.len() != names.actuators.len()) || names.joints.is_empty() {
        return Err(bind.error(format!(
            "{} joints and {} actuators: a serial arm names one actuator per joint (or none, \
             to use the actuator that drives each joint)",
            names.joints.len(),
            names.actuators.len()
        )));
    }
    for list in [names.joints, names.actuators] {
        if let Some(repeated) = list
            .iter()
            .enumerate()
            .find(|(i, name)| list[..*i].contains(name))
        {
            return Err(bind.error(format!(
                "{:?} is named twice in the mapping: each joint of a serial arm, and each \
                 actuator, is named once",
                repeated.1
            )));
        }
    }
    let joints = names
        .joints
        .iter()
        .map(|name| bind.joint(name))
        .collect::<Result<Vec<_>, _>>()?;
    let mut drives = Vec::with_capacity(names.joints.len());
    for (index, (&name, joint)) in names.joints.iter().zip(&joints).enumerate() {
        let (actuator, actuator_name) = match names.actuators.get(index) {
            Some(&actuator_name) => (bind.actuator(actuator_name)?, actuator_name.to_owned()),
            None => {
                let actuator = bind
                    .actuator_driving(joint)
                    .map_err(|error| moved_by_mocap(bind, joint, name).unwrap_or(error))?;
                let model = bind.backend().model();
                let described = model
                    .actuator_name(actuator.id())
                    .unwrap_or_else(|| format!("the actuator of {name}"));
                (actuator, described)
            }
        };
        let model = std::sync::Arc::clone(bind.backend().model());
        if let Some(driven) = model.actuator_joint(actuator.id())
            && driven != joint.id()
        {
            let driven = joints
                .iter()
                .position(|joint| joint.id() == driven)
                .map(|i| names.joints[i].to_owned())
                .or_else(|| model.joint_name(driven))
                .unwrap_or_default();
            return Err(bind.error(format!(
                "actuator {actuator_name:?} drives joint {driven:?}, not {name:?}: the \
                 mapping's actuators are in the order of its joints (are two swapped?)"
            )));
        }
        let actuation = match (model.motor_gear(actuator.id()), actuator.servo_gains()) {
            (Some(gear), _) => Actuation::Motor { gear },
            (None, Some(gains)) => Actuation::Servo(gains),
            (None, None) => {
                return Err(bind.error(format!(
                    "actuator {actuator_name:?} is neither a motor (<motor>) nor a position \
                     servo on its joint: a serial arm drives one of these"
                )));
            }
        };
        let force_range = force_range(&model, &actuator, actuation, joint);
        drives.push(ActuatedJoint {
            name: name.to_owned(),
            losses: model.joint_losses(joint.id()),
            joint: joint.clone(),
            actuator,
            actuation,
            force_range,
        });
    }
    Ok(drives)
}

/// Why `joint` has no actuator when the file moves the arm by a weld to a mocap body (an
/// end-effector-controlled file, as gym-aloha's `…_end_effector_…` scenes): the refusal naming
/// the weld, or `None`.
fn moved_by_mocap(bind: &Bind<Sim>, joint: &Joint, name: &str) -> Option<BindError> {
    let model = bind.backend().model();
    let moved = model.joint_body(joint.id());
    let weld = model
        .mocap_welds()
        .into_iter()
        .find(|weld| model.carries(moved, weld.held))?;
    let body = |id| {
        model
            .body_name(id)
            .unwrap_or_else(|| "an unnamed body".to_owned())
    };
    let named = weld
        .name
        .map_or_else(String::new, |name| format!(" {name:?}"));
    Some(bind.error(format!(
        "joint {name:?} has no actuator: the file moves the arm by the weld{named} of mocap \
         body {:?} to {:?}, the hand following the mocap body's pose; a serial arm is driven \
         through its joints' actuators: use the file's joint-actuated variant, or give each \
         joint a <position> actuator",
        body(weld.mocap),
        body(weld.held)
    )))
}

/// The force range an actuator puts on its joint: its control range (a motor's) and force
/// range through its gear, within the joint's own limit on actuator force.
fn force_range(
    model: &Model,
    actuator: &Actuator,
    actuation: Actuation,
    joint: &Joint,
) -> [f64; 2] {
    let unlimited = [f64::NEG_INFINITY, f64::INFINITY];
    let intersect = |[a, b]: [f64; 2], [c, d]: [f64; 2]| [a.max(c), b.min(d)];
    let through = |[a, b]: [f64; 2], gear: f64| {
        let (a, b) = (a * gear, b * gear);
        [a.min(b), a.max(b)]
    };
    let gear = match actuation {
        Actuation::Motor { gear } => gear,
        Actuation::Servo(gains) => gains.gear,
    };
    let mut range = model
        .actuator_force_range(actuator.id())
        .map_or(unlimited, |range| through(range, gear));
    if let (Actuation::Motor { .. }, Some(control)) = (actuation, actuator.ctrl_range()) {
        range = intersect(range, through(control, gear));
    }
    if let Some(joint_range) = model.joint_force_range(joint.id()) {
        range = intersect(range, joint_range);
    }
    range
}
