//! The [`AnetA30`]'s `real` interface: a Marlin printer on a serial port, driven by a task that
//! sends each new target, waits for the moves to finish (`M400`) and reads where the head is.

use std::cell::Cell;
use std::rc::Rc;
use std::time::Duration;

use serde::Deserialize;
use tokio::sync::{Mutex, watch};
use yarok_core::component::{Bind, BindError, Interface};
use yarok_hw::marlin::{Marlin, MarlinSettings, Position};
use yarok_hw::{Real, SerialPort};

use super::{AnetA30, Axes};

/// The interface settings of a real printer (`[interfaces."/printer"]`).
#[derive(Debug, Clone, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct Settings {
    /// The serial device.
    port: String,
    /// Bits a second (Geeetech A30 stock firmware: 115 200).
    baud: u32,
    /// Feed rate of moves, mm/s.
    feed: f64,
    /// Whether to home the axes (`G28`) when the run starts.
    home: bool,
    /// Seconds the board may take to boot after the port opens.
    boot_seconds: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            port: "/dev/ttyUSB0".into(),
            baud: 115_200,
            feed: 50.0,
            home: true,
            boot_seconds: 10.0,
        }
    }
}

/// The head as the driver's task keeps it: the newest target asked for, and where the printer
/// last said the head was after finishing its moves.
pub(super) struct RealAxes {
    target: watch::Sender<Option<[f64; 3]>>,
    at: Cell<[f64; 3]>,
}

impl RealAxes {
    pub(super) fn move_to(&self, target: [f64; 3]) {
        self.target.send_replace(Some(target));
    }

    pub(super) fn at(&self) -> [f64; 3] {
        self.at.get()
    }
}

impl Interface<Real> for AnetA30 {
    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        let settings: Settings = bind.settings()?;
        if !(settings.feed > 0.0 && settings.feed.is_finite()) {
            return Err(bind.error(format!(
                "feed must be a positive speed, not {}",
                settings.feed
            )));
        }
        let port = SerialPort::open(&settings.port, settings.baud).map_err(|e| bind.error(e))?;
        let mut marlin_settings = MarlinSettings::new(settings.port.clone());
        marlin_settings.boot_timeout = Duration::from_secs_f64(settings.boot_seconds.max(0.0));
        let mut marlin = Marlin::connect(port, marlin_settings)
            .await
            .map_err(|e| bind.error(e))?;
        let start = async {
            if settings.home {
                marlin.home().await?;
            } else {
                marlin.command("G90").await?;
            }
            marlin.position().await
        };
        let Position { x, y, z } = start.await.map_err(|e| bind.error(e))?;
        let axes = Rc::new(RealAxes {
            target: watch::Sender::new(None),
            at: Cell::new([x, y, z]),
        });
        let marlin = Rc::new(Mutex::new(marlin));
        bind.spawn(drive(Rc::clone(&axes), Rc::clone(&marlin), settings.feed));
        bind.on_stop(async move {
            marlin.lock().await.quick_stop().await?;
            Ok(())
        });
        Ok(AnetA30 {
            axes: Axes::Real(axes),
        })
    }
}

/// Sends each newest target to the printer, waits for the moves to finish and records where
/// the head then is; ends the run with the printer's error if one comes.
async fn drive(
    axes: Rc<RealAxes>,
    marlin: Rc<Mutex<Marlin<SerialPort>>>,
    feed: f64,
) -> Result<(), yarok_core::BoxError> {
    let mut targets = axes.target.subscribe();
    while targets.changed().await.is_ok() {
        let Some(target) = *targets.borrow_and_update() else {
            continue;
        };
        let mut marlin = marlin.lock().await;
        marlin.move_to(target, feed).await?;
        marlin.finish_moves().await?;
        let Position { x, y, z } = marlin.position().await?;
        axes.at.set([x, y, z]);
    }
    Ok(())
}
