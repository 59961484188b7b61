//! A linear slide: a carriage moved along its rail to a position in millimetres.

mod mock;
mod real;
mod replay;
mod sim;

use std::rc::Rc;

use yarok::prelude::*;

pub(crate) use replay::Replay;

/// The slide's carriage in one environment.
pub(crate) trait SlideDrive {
    /// Starts moving the carriage to `mm` along the rail.
    fn move_to(&self, mm: f64);
    /// Where the carriage is (mm).
    fn at(&self) -> f64;
}

/// A slide, over its carriage in one environment.
#[derive(Clone)]
pub(crate) struct Slide {
    drive: Rc<dyn SlideDrive>,
    clock: Clock,
}

impl Slide {
    fn new<E: Environment>(bind: &Bind<E>, drive: impl SlideDrive + 'static) -> Self {
        Self {
            drive: Rc::new(drive),
            clock: bind.clock(),
        }
    }

    /// Where the carriage is (mm).
    pub(crate) fn at(&self) -> f64 {
        self.drive.at()
    }

    /// Moves the carriage to `mm`; resolves once it is within 0.1 mm (at most 10 s).
    pub(crate) async fn move_to(&self, mm: f64) -> Result<(), WaitError> {
        self.drive.move_to(mm);
        let there = || (self.at() - mm).abs() < 0.1;
        self.clock.wait(there).timeout(10.0).await
    }
}

impl Component for Slide {
    fn declaration() -> Declaration {
        Declaration::new("slide").template(include_str!("slide.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>();
        interfaces.add::<Real>().add::<Replay>();
    }
}
