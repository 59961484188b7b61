//! [`AxesDrive`]: how the printer's head is moved in one environment.

/// The printer's three axes in one environment: MuJoCo's servos, a mock, a Marlin printer, or
/// a user's own. [`AnetA30`](super::AnetA30) clamps every target to the work volume before it
/// reaches a drive, and calls nothing else.
pub trait AxesDrive {
    /// Starts moving the head to `target` (millimetres, inside the work volume).
    fn move_to(&self, target: [f64; 3]);

    /// Puts the head at `target` at once and at rest, where the environment can (a
    /// simulation); by default, [`AxesDrive::move_to`].
    fn place(&self, target: [f64; 3]) {
        self.move_to(target);
    }

    /// Where the head is, in millimetres.
    fn at(&self) -> [f64; 3];
}
