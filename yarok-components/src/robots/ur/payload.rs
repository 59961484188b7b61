//! [`Payload`]: what the arm carries at its flange (a tool, a grasped object), as the UR
//! controller's `set_payload` states it.

/// A payload: its mass and where its centre of gravity is in the flange (`tool0`) frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Payload {
    /// Kilograms.
    pub mass: f64,
    /// Metres, in the flange frame.
    pub centre: [f64; 3],
}

impl Payload {
    /// A payload of `mass` kilograms centred at `centre` (metres, flange frame).
    ///
    /// # Errors
    ///
    /// When the mass is negative or a number is not finite.
    pub fn new(mass: f64, centre: [f64; 3]) -> Result<Self, String> {
        if !(mass >= 0.0 && mass.is_finite() && centre.iter().all(|c| c.is_finite())) {
            return Err(format!(
                "payload mass {mass} kg at {centre:?} m: the mass must be a number ≥ 0 and the \
                 centre finite"
            ));
        }
        Ok(Self { mass, centre })
    }
}
