//! [`Servos`]: an arm in `sim` — its joints' position servos, fed forward as the UR controller
//! does.

use nalgebra::Point3;
use yarok_core::component::{Bind, BindError};
use yarok_mjc::{Actuator, Joint, ServoGains, Sim, SimBind, Site};

use super::config::ArmNames;
use super::drive::{ArmDrive, Setpoint};
use super::kinematics::Joints;
use super::measured::isometry_of;
use super::payload::Payload;

/// The joints and position servos of an arm in `sim`, with the servos' gains as the model
/// states them, its flange site and the world's gravity (for the payload).
pub(super) struct Servos {
    joints: [Joint; 6],
    servos: [Actuator; 6],
    gains: [ServoGains; 6],
    flange: Site,
    gravity: [f64; 3],
}

impl Servos {
    /// The arm's joints and servos by their `names`, each servo's gains read from the model.
    ///
    /// # Errors
    ///
    /// [`BindError`] when the model lacks a part or an actuator is not a position servo.
    pub(super) fn bind(bind: &mut Bind<Sim>, names: &ArmNames) -> Result<Self, BindError> {
        let mut joints = Vec::with_capacity(6);
        let mut servos = Vec::with_capacity(6);
        for (joint, servo) in names.joints.iter().zip(names.actuators) {
            joints.push(bind.joint(joint)?);
            servos.push(bind.actuator(servo)?);
        }
        let joints: [Joint; 6] = joints.try_into().map_err(|_| bind.error("six joints"))?;
        let servos: [Actuator; 6] = servos.try_into().map_err(|_| bind.error("six servos"))?;
        let mut gains = Vec::with_capacity(6);
        for (servo, name) in servos.iter().zip(names.actuators) {
            gains.push(servo.servo_gains().ok_or_else(|| {
                bind.error(format!(
                    "actuator {name:?} is not a position servo on its joint (a fixed gain and an \
                     affine bias, as <position> or <general biastype=\"affine\">): the arm \
                     drives position servos"
                ))
            })?);
        }
        Ok(Self {
            joints,
            servos,
            gains: gains.try_into().map_err(|_| bind.error("six servos"))?,
            flange: bind.site(names.flange)?,
            gravity: bind.backend().model().ffi().opt.gravity,
        })
    }

    /// Puts the joints at `start`, where given (else they stay where the model has them);
    /// where they are.
    pub(super) fn start_at(&self, start: Option<Joints>) -> Joints {
        for (joint, angle) in self.joints.iter().zip(start.iter().flatten()) {
            joint.set_position(*angle);
        }
        self.joints.each_ref().map(Joint::position)
    }

    /// What each joint must give to hold `payload` against gravity.
    fn holding(&self, payload: &Payload) -> Vec<f64> {
        let centre = isometry_of(&self.flange.pose()) * Point3::from(payload.centre);
        let weight = self.gravity.map(|g| -g * payload.mass);
        self.flange
            .forces_on(&self.joints, centre.coords.into(), weight)
    }
}

impl ArmDrive for Servos {
    fn q(&self, _commanded: &Setpoint) -> Joints {
        self.joints.each_ref().map(Joint::position)
    }

    fn qd(&self, _commanded: &Setpoint) -> Joints {
        self.joints.each_ref().map(Joint::velocity)
    }

    /// Sets the servos to the setpoint, with what the arm's controller adds as a real one
    /// does: the force that the setpoint's speed and acceleration take and that gravity,
    /// Coriolis and centrifugal forces ask of each joint (those the model does not compensate
    /// itself), and the payload's weight, so that the joints track without lag or sag.
    fn command(&self, setpoint: &Setpoint) {
        let payload = match &setpoint.payload {
            Some(payload) if payload.mass > 0.0 => self.holding(payload),
            _ => vec![0.0; 6],
        };
        for (i, gains) in self.gains.iter().enumerate() {
            let joint = &self.joints[i];
            let torque =
                joint.inertia() * setpoint.acceleration[i] + joint.bias_force() + payload[i];
            // The servo's force is gain·ctrl − kp·gear·q − kv·gear·q̇; the joint feels gear
            // times it.
            let force = gains.gear * (gains.kp * setpoint.q[i] + gains.kv * setpoint.speed[i])
                + torque / gains.gear;
            self.servos[i].set(force / gains.gain);
        }
    }

    fn is_put_back_at_restart(&self) -> bool {
        true
    }
}
