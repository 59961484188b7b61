//! [`MockAxes`]: a head that is wherever it was last sent.

use std::cell::Cell;

use super::drive::AxesDrive;

/// Axes with no physics: the head moves instantly.
#[derive(Default)]
pub(super) struct MockAxes {
    at: Cell<[f64; 3]>,
}

impl AxesDrive for MockAxes {
    fn move_to(&self, target: [f64; 3]) {
        self.at.set(target);
    }

    fn at(&self) -> [f64; 3] {
        self.at.get()
    }
}
