//! [`SimAxes`]: the printer's axes in MuJoCo.

use yarok_core::component::{Bind, BindError};
use yarok_mjc::{Actuator, Joint, Sensor, Sim, SimBind};

use super::drive::AxesDrive;

/// The axes in MuJoCo: position servos (metres), their measured positions, and the joints
/// themselves.
pub(super) struct SimAxes {
    servos: [Actuator; 3],
    positions: [Sensor; 3],
    joints: [Joint; 3],
}

impl SimAxes {
    /// The axes `x`, `y` and `z`: each a servo, a position sensor and a joint of that name.
    pub(super) fn bind(bind: &Bind<Sim>) -> Result<Self, BindError> {
        let [x, y, z] = ["x", "y", "z"];
        Ok(Self {
            servos: [bind.actuator(x)?, bind.actuator(y)?, bind.actuator(z)?],
            positions: [bind.sensor(x)?, bind.sensor(y)?, bind.sensor(z)?],
            joints: [bind.joint(x)?, bind.joint(y)?, bind.joint(z)?],
        })
    }
}

impl AxesDrive for SimAxes {
    fn move_to(&self, target: [f64; 3]) {
        for (servo, mm) in self.servos.iter().zip(target) {
            servo.set(mm / 1000.0);
        }
    }

    /// The servos' targets, and the joints set there at rest, so that where the head is
    /// afterwards does not depend on earlier moves.
    fn place(&self, target: [f64; 3]) {
        self.move_to(target);
        for (joint, mm) in self.joints.iter().zip(target) {
            joint.set_position(mm / 1000.0);
        }
    }

    fn at(&self) -> [f64; 3] {
        self.positions.each_ref().map(|axis| axis.value() * 1000.0)
    }
}
