//! The slide in `sim`: a position servo on the carriage's slide joint.

use super::*;

/// The carriage's slide joint and the position servo on it.
impl SlideDrive for (Joint, Actuator) {
    fn move_to(&self, mm: f64) {
        self.1.set(mm / 1000.0);
    }

    fn at(&self) -> f64 {
        self.0.position() * 1000.0
    }
}

impl Interface<Sim> for Slide {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let drive = (bind.joint("rail")?, bind.actuator("rail")?);
        Ok(Slide::new(bind, drive))
    }
}
