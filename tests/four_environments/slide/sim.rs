//! The slide in `sim`: a position servo on the carriage's slide joint.

use yarok::prelude::*;

use super::{Slide, SlideDrive};

struct Servo {
    joint: Joint,
    servo: Actuator,
}

impl SlideDrive for Servo {
    fn move_to(&self, mm: f64) {
        self.servo.set(mm / 1000.0);
    }

    fn at(&self) -> f64 {
        self.joint.position() * 1000.0
    }
}

impl Interface<Sim> for Slide {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let (joint, servo) = (bind.joint("rail")?, bind.actuator("rail")?);
        Ok(Slide::new(bind, Servo { joint, servo }))
    }
}
