//! [`NamedActuation`]: the targets a component's actuators follow, as a policy sets them and a
//! dataset records them — one number per actuator.

use super::Named;
use crate::BoxError;

/// What sets a component's actuators' targets.
type SetTargets = Box<dyn Fn(&[f64]) -> Result<(), BoxError>>;

/// What a component's actuators are driven by: their names, where they are and the targets
/// they follow now, and how a new target is set.
pub struct Actuators {
    pub(crate) names: Vec<String>,
    pub(crate) ranges: Vec<[f64; 2]>,
    pub(crate) measured: Box<dyn Fn() -> Vec<f64>>,
    pub(crate) target: Box<dyn Fn(f64) -> Vec<f64>>,
    pub(crate) set: SetTargets,
}

impl std::fmt::Debug for Actuators {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Actuators")
            .field("names", &self.names)
            .finish()
    }
}

/// A component's actuation: registered with [`Bind::actuation`](super::Bind::actuation),
/// listed to plugins by [`World::actuations`](crate::runtime::World::actuations). The world's
/// action is every actuation's targets, in binding order.
pub type NamedActuation = Named<Actuators>;

impl NamedActuation {
    /// The actuators' names, as the composed model names them (`arm/shoulder_pan`).
    pub fn names(&self) -> &[String] {
        &self.function().names
    }

    /// The range of each actuator's target, lowest first (a joint's limits, a gripper's 0–255).
    pub fn ranges(&self) -> &[[f64; 2]] {
        &self.function().ranges
    }

    /// Where the actuators are now, as measured, in the targets' units (an arm's joint
    /// positions, a gripper's position): in any environment, what a policy observes of them.
    pub fn measured(&self) -> Vec<f64> {
        (self.function().measured)()
    }

    /// The targets the actuators are commanded to reach `ahead` seconds from now, one per
    /// name: a streamed target (a policy's action), where a motion under way is due then (an
    /// arm's joints), a commanded position (a gripper's). What a policy must output now for
    /// the next `ahead` seconds to go as they are going: a dataset's `action`.
    pub fn target(&self, ahead: f64) -> Vec<f64> {
        (self.function().target)(ahead)
    }

    /// Sets new targets, one per name, which the actuators follow from the next tick.
    ///
    /// # Errors
    ///
    /// When `targets` has not one number per actuator, one is outside its range or not a
    /// number, or the component refuses them, naming the actuation
    /// (`actuation /arm/action: …`).
    pub fn set(&self, targets: &[f64]) -> Result<(), BoxError> {
        self.check(targets)?;
        (self.function().set)(targets).map_err(|e| format!("actuation {}: {e}", self.path()).into())
    }

    /// Whether [`NamedActuation::set`] would take `targets` as far as the names and ranges go:
    /// how a world's action is checked whole before any component's share is set.
    ///
    /// # Errors
    ///
    /// As [`NamedActuation::set`]'s, but for the component's own refusal.
    pub fn check(&self, targets: &[f64]) -> Result<(), BoxError> {
        let names = self.names();
        if targets.len() != names.len() {
            return Err(format!(
                "actuation {}: {} targets given for {} actuators ({})",
                self.path(),
                targets.len(),
                names.len(),
                names.join(", ")
            )
            .into());
        }
        let outside =
            |(target, [lowest, highest]): (&f64, &[f64; 2])| !(*lowest..=*highest).contains(target);
        if let Some(at) = targets.iter().zip(self.ranges()).position(outside) {
            let [lowest, highest] = self.ranges()[at];
            return Err(format!(
                "actuation {}: the target of {} is {}, outside its range {lowest} to {highest}",
                self.path(),
                names[at],
                targets[at]
            )
            .into());
        }
        Ok(())
    }
}
