//! The slide in `mock`: the carriage is where it is sent, at once.

use std::cell::Cell;

use super::*;

impl SlideDrive for Cell<f64> {
    fn move_to(&self, mm: f64) {
        self.set(mm);
    }

    fn at(&self) -> f64 {
        self.get()
    }
}

impl Interface<Mock> for Slide {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Ok(Slide::new(bind, Cell::new(0.0)))
    }
}
