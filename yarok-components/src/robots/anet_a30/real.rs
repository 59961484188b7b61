//! The [`AnetA30`]'s `real` interface: a Marlin printer on a serial port, driven by a task that
//! sends each new target, waits for the moves to finish (`M400`) and reads where the head is;
//! a printer unplugged and plugged back in is reconnected.

use std::cell::Cell;
use std::rc::Rc;
use std::time::Duration;

use serde::Deserialize;
use tokio::sync::{Mutex, watch};
use yarok_core::component::{Bind, BindError, Interface};
use yarok_hw::marlin::{Marlin, MarlinError, MarlinSettings, Position, Reconnecting};
use yarok_hw::{Real, SerialPort};

use super::{AnetA30, AxesDrive};

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
    /// Seconds an unplugged printer may take to come back before the run ends with an error.
    replug_seconds: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            port: "/dev/ttyUSB0".into(),
            baud: 115_200,
            feed: 50.0,
            home: true,
            boot_seconds: 10.0,
            replug_seconds: 30.0,
        }
    }
}

/// The head as the driver's task keeps it: the newest target asked for, and where the printer
/// last said the head was after finishing its moves.
struct RealAxes {
    target: watch::Sender<Option<[f64; 3]>>,
    at: Cell<[f64; 3]>,
}

impl AxesDrive for RealAxes {
    fn move_to(&self, target: [f64; 3]) {
        self.target.send_replace(Some(target));
    }

    fn at(&self) -> [f64; 3] {
        self.at.get()
    }
}

/// The printer's interface settings, checked.
fn settings(bind: &Bind<Real>) -> Result<Settings, BindError> {
    let settings: Settings = bind.settings()?;
    if !(settings.feed > 0.0 && settings.feed.is_finite()) {
        return Err(bind.error(format!(
            "feed must be a positive speed, not {}",
            settings.feed
        )));
    }
    Ok(settings)
}

impl Interface<Real> for AnetA30 {
    fn check(bind: &Bind<Real>) -> Result<(), BindError> {
        settings(bind).map(drop)
    }

    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        let settings = settings(bind)?;
        let mut marlin_settings = MarlinSettings::new(settings.port.clone());
        let seconds = |value: f64| Duration::try_from_secs_f64(value).unwrap_or_default();
        marlin_settings.boot_timeout = seconds(settings.boot_seconds);
        marlin_settings.replug_timeout = seconds(settings.replug_seconds);
        let (port, baud) = (settings.port.clone(), settings.baud);
        let open = async move || SerialPort::open(&port, baud);
        let mut printer = Reconnecting::connect(open, marlin_settings)
            .await
            .map_err(|e| bind.error(e))?;
        let home = settings.home;
        let start = async |marlin: &mut Marlin<SerialPort>| {
            if home {
                marlin.home().await?;
            } else {
                marlin.use_absolute_coordinates().await?;
            }
            marlin.position().await
        };
        let Position { x, y, z } = printer.run(start).await.map_err(|e| bind.error(e))?;
        let axes = Rc::new(RealAxes {
            target: watch::Sender::new(None),
            at: Cell::new([x, y, z]),
        });
        let printer = Rc::new(Mutex::new(printer));
        bind.spawn(drive(Rc::clone(&axes), Rc::clone(&printer), settings));
        bind.on_stop(async move {
            // A printer that went away is not waited for: it stopped when it restarted.
            if let Some(marlin) = printer.lock().await.connected() {
                marlin.quick_stop().await?;
            }
            Ok(())
        });
        Ok(AnetA30::with_drive(bind, axes))
    }
}

/// Sends each newest target to the printer, waits for the moves to finish and records where
/// the head then is; ends the run with the printer's error if one comes. A printer that was
/// unplugged and came back mid-move is homed again and sent the target again when homing is
/// on (without homing its position is unknown, and the run ends with the error).
async fn drive<O, E>(
    axes: Rc<RealAxes>,
    printer: Rc<Mutex<Reconnecting<SerialPort, O>>>,
    settings: Settings,
) -> Result<(), yarok_core::BoxError>
where
    O: AsyncFnMut() -> Result<SerialPort, E>,
    E: std::error::Error + Send + Sync + 'static,
{
    let feed = settings.feed;
    let mut targets = axes.target.subscribe();
    while targets.changed().await.is_ok() {
        let Some(target) = *targets.borrow_and_update() else {
            continue;
        };
        let mut printer = printer.lock().await;
        let at = match printer.run(async |m| arrive(m, target, feed).await).await {
            Err(error @ MarlinError::Reconnected { .. }) if settings.home => {
                tracing::warn!("{error}; homing it and moving again");
                let again = async |m: &mut Marlin<SerialPort>| {
                    m.home().await?;
                    arrive(m, target, feed).await
                };
                printer.run(again).await?
            }
            other => other?,
        };
        axes.at.set([at.x, at.y, at.z]);
    }
    Ok(())
}

/// Moves to `target`, waits for the move to finish and reads where the head is.
async fn arrive(
    marlin: &mut Marlin<SerialPort>,
    target: [f64; 3],
    feed: f64,
) -> Result<Position, MarlinError> {
    marlin.move_to(target, feed).await?;
    marlin.finish_moves().await?;
    marlin.position().await
}
