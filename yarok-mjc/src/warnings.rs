//! [`Warnings`]: how many times MuJoCo has raised each kind of warning in a simulation — how a
//! caller learns that a step went wrong (an unstable state MuJoCo reset, a full contact buffer)
//! rather than finding the world somewhere else without a word.

use crate::sys;

/// MuJoCo's warning kinds, by `mjtWarning`, in words.
const KINDS: [(sys::mjtWarning, &str); 7] = [
    (
        sys::mjWARN_INERTIA,
        "an inertia too small or not positive definite",
    ),
    (
        sys::mjWARN_CONTACTFULL,
        "more contacts than the contact buffer holds (some were left out)",
    ),
    (
        sys::mjWARN_CNSTRFULL,
        "more constraints than the buffer holds (some were left out)",
    ),
    (
        sys::mjWARN_BADQPOS,
        "a position that is not a number or too large (the state was reset)",
    ),
    (
        sys::mjWARN_BADQVEL,
        "a velocity that is not a number or too large (the state was reset)",
    ),
    (
        sys::mjWARN_BADQACC,
        "an unstable acceleration, not a number or too large (the state was reset)",
    ),
    (
        sys::mjWARN_BADCTRL,
        "a control that is not a number or too large (it was zeroed)",
    ),
];

/// How many times each kind of warning was raised in a simulation since its state was made or
/// reset ([`Data::warnings`](crate::Data::warnings)).
///
/// # Examples
///
/// ```
/// use std::sync::Arc;
/// use yarok_mjc::{Data, Model};
///
/// let model = Arc::new(Model::from_xml_str(
///     r#"<mujoco><worldbody><body><joint name="hinge"/><geom size="0.1"/></body>
///        </worldbody><actuator><motor name="push" joint="hinge"/></actuator></mujoco>"#,
/// )?);
/// let mut data = Data::new(&model)?;
/// let before = data.warnings();
/// data.set_ctrl(model.actuator("push")?, f64::NAN);
/// data.step();
/// let raised = data.warnings().since(&before);
/// assert_eq!(raised.len(), 1, "a NaN control is reported: {raised:?}");
/// assert!(raised[0].contains("control"));
/// # Ok::<(), yarok_mjc::ModelError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Warnings([i32; KINDS.len()]);

impl Warnings {
    pub(crate) fn of(data: &sys::mjData) -> Self {
        Self(std::array::from_fn(|i| {
            data.warning[KINDS[i].0 as usize].number
        }))
    }

    /// What was raised since `earlier` (of the same simulation), in words, one per kind.
    pub fn since(&self, earlier: &Warnings) -> Vec<&'static str> {
        KINDS
            .iter()
            .zip(self.0.iter().zip(earlier.0))
            .filter(|(_, (now, before))| **now > *before)
            .map(|((_, words), _)| *words)
            .collect()
    }
}
