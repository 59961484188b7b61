//! The slide in `real`: the X axis of a Marlin board on a serial port (interface setting
//! `port`), homed at the start and quick-stopped at shutdown.

use std::cell::Cell;
use std::rc::Rc;

use tokio::sync::{Mutex, watch};
use yarok::hw::SerialPort;
use yarok::hw::marlin::{Marlin, MarlinSettings};
use yarok::prelude::*;

use super::{Slide, SlideDrive};

/// Feed rate of the moves (mm/s).
const FEED: f64 = 50.0;

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Settings {
    port: String,
}

/// The newest target, and where the board last said the carriage was.
struct MarlinAxis {
    target: watch::Sender<Option<f64>>,
    at: Rc<Cell<f64>>,
}

impl SlideDrive for MarlinAxis {
    fn move_to(&self, mm: f64) {
        self.target.send_replace(Some(mm));
    }

    fn at(&self) -> f64 {
        self.at.get()
    }
}

impl Interface<Real> for Slide {
    fn check(bind: &Bind<Real>) -> Result<(), BindError> {
        bind.settings::<Settings>().map(drop)
    }

    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        let Settings { port } = bind.settings()?;
        let serial = SerialPort::open(&port, 250_000).map_err(|e| bind.error(e))?;
        let mut marlin = Marlin::connect(serial, MarlinSettings::new(port))
            .await
            .map_err(|e| bind.error(e))?;
        marlin.home().await.map_err(|e| bind.error(e))?;
        let at = Rc::new(Cell::new(
            marlin.position().await.map_err(|e| bind.error(e))?.x,
        ));
        let (target, targets) = watch::channel(None);
        let marlin = Rc::new(Mutex::new(marlin));
        bind.spawn(follow(targets, Rc::clone(&at), Rc::clone(&marlin)));
        bind.on_stop(async move { Ok(marlin.lock().await.quick_stop().await?) });
        Ok(Slide::new(bind, MarlinAxis { target, at }))
    }
}

/// Sends each newest target, waits for the move to finish and reads where the carriage is.
async fn follow(
    mut targets: watch::Receiver<Option<f64>>,
    at: Rc<Cell<f64>>,
    marlin: Rc<Mutex<Marlin<SerialPort>>>,
) -> Result<(), BoxError> {
    while targets.changed().await.is_ok() {
        let Some(x) = *targets.borrow_and_update() else {
            continue;
        };
        let mut marlin = marlin.lock().await;
        marlin.move_to([x, 0.0, 0.0], FEED).await?;
        marlin.finish_moves().await?;
        at.set(marlin.position().await?.x);
    }
    Ok(())
}
