//! A user's own environment, `replay`: the carriage is where a recording says it was, whatever
//! it is sent to.

use yarok::core::component::MockBackend;
use yarok::prelude::*;

use super::{Slide, SlideDrive};

/// Runs that replay a recording.
pub(crate) struct Replay;

impl Environment for Replay {
    const NAME: &'static str = "replay";
    type Backend = MockBackend;
}

/// A recording: the carriage going to 50 mm over the first second, then back to 20 mm over
/// the next, sampled every 10 ms.
fn recording() -> Vec<(f64, f64)> {
    (0..=200)
        .map(|step| {
            let time = f64::from(step) / 100.0;
            let at = if time <= 1.0 {
                50.0 * time
            } else {
                50.0 - 30.0 * (time - 1.0)
            };
            (time, at)
        })
        .collect()
}

struct Replayed {
    clock: Clock,
    track: Vec<(f64, f64)>,
}

impl SlideDrive for Replayed {
    fn move_to(&self, _mm: f64) {}

    fn at(&self) -> f64 {
        let now = self.clock.time();
        let passed = self.track.iter().take_while(|(time, _)| *time <= now);
        passed.last().map_or(0.0, |(_, at)| *at)
    }
}

impl Interface<Replay> for Slide {
    async fn bind(bind: &mut Bind<Replay>) -> Result<Self, BindError> {
        let clock = bind.clock();
        let track = recording();
        Ok(Slide::new(bind, Replayed { clock, track }))
    }
}
