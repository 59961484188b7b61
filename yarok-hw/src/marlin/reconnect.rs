//! [`Reconnecting`]: a Marlin printer opened again when its connection drops — a USB printer
//! unplugged and plugged back in.

use tokio::io::{AsyncRead, AsyncWrite};

use super::{Marlin, MarlinError, MarlinSettings};
use crate::reopen;

/// Why the last attempt to reconnect failed.
type Failure = Box<dyn std::error::Error + Send + Sync>;

/// A [`Marlin`] printer that is reconnected when its connection drops: the transport is opened
/// again with the function it was made with (for a serial port, the device path — a stable one
/// such as `/dev/serial/by-id/…` survives the board coming back under another name), and the
/// board is let boot again, within [`MarlinSettings::replug_timeout`].
///
/// A board that comes back has restarted: it lost its queue and its position. The work that
/// was running when the connection dropped is therefore reported as failed, with
/// [`MarlinError::Reconnected`], never re-sent or silently lost; the caller decides what to do
/// (home and move again, or give up). A printer that does not come back in time is a
/// [`MarlinError::Unplugged`], and the next call looks for it again.
///
/// ```no_run
/// # async fn run() -> Result<(), yarok_hw::marlin::MarlinError> {
/// use yarok_hw::SerialPort;
/// use yarok_hw::marlin::{MarlinError, MarlinSettings, Reconnecting};
///
/// let path = "/dev/serial/by-id/usb-1a86_USB2.0-Serial-if00-port0";
/// let open = async || SerialPort::open(path, 115_200);
/// let mut printer = Reconnecting::connect(open, MarlinSettings::new(path)).await?;
/// printer.run(async |marlin| marlin.home().await).await?;
/// let square = async |marlin: &mut yarok_hw::marlin::Marlin<SerialPort>| {
///     for corner in [[10.0, 10.0, 5.0], [60.0, 10.0, 5.0], [60.0, 60.0, 5.0]] {
///         marlin.move_to(corner, 50.0).await?;
///     }
///     marlin.finish_moves().await
/// };
/// match printer.run(square).await {
///     Err(MarlinError::Reconnected { .. }) => { /* home again and start over */ }
///     other => other?,
/// }
/// # Ok(()) }
/// ```
///
/// # Cancel safety
///
/// [`Reconnecting::run`] is as cancel safe as the work it runs; dropped while reconnecting, the
/// next call reconnects.
pub struct Reconnecting<T, O> {
    open: O,
    settings: MarlinSettings,
    marlin: Option<Marlin<T>>,
}

impl<T, O> std::fmt::Debug for Reconnecting<T, O> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Reconnecting")
            .field("printer", &self.settings.name)
            .field("connected", &self.marlin.is_some())
            .finish()
    }
}

impl<T, O, E> Reconnecting<T, O>
where
    T: AsyncRead + AsyncWrite + Unpin,
    O: AsyncFnMut() -> Result<T, E>,
    E: std::error::Error + Send + Sync + 'static,
{
    /// Opens the transport with `open` and connects as [`Marlin::connect`] does.
    ///
    /// # Errors
    ///
    /// [`MarlinError::Open`] when `open` fails; [`Marlin::connect`]'s errors.
    pub async fn connect(mut open: O, settings: MarlinSettings) -> Result<Self, MarlinError> {
        let transport = open().await.map_err(|source| MarlinError::Open {
            printer: settings.name.clone(),
            source: Box::new(source),
        })?;
        let marlin = Marlin::connect(transport, settings.clone()).await?;
        Ok(Self {
            open,
            settings,
            marlin: Some(marlin),
        })
    }

    /// The printer when it is connected now; `None` after its connection dropped and before it
    /// came back. For work that must not wait for a reconnection, such as a stop at shutdown.
    pub fn connected(&mut self) -> Option<&mut Marlin<T>> {
        self.marlin.as_mut()
    }

    /// Runs `work` on the printer, first reconnecting it if its connection dropped earlier.
    ///
    /// # Errors
    ///
    /// `work`'s error; [`MarlinError::Reconnected`] when the connection dropped during `work`
    /// and the printer came back; [`MarlinError::Unplugged`] when it did not come back within
    /// [`MarlinSettings::replug_timeout`].
    pub async fn run<R>(
        &mut self,
        work: impl AsyncFnOnce(&mut Marlin<T>) -> Result<R, MarlinError>,
    ) -> Result<R, MarlinError> {
        let marlin = match &mut self.marlin {
            Some(marlin) => marlin,
            None => self.reconnect().await?,
        };
        match work(marlin).await {
            Err(error) if error.is_connection_lost() => {
                self.marlin = None;
                self.reconnect().await?;
                Err(MarlinError::Reconnected {
                    printer: self.settings.name.clone(),
                    cause: Box::new(error),
                })
            }
            other => other,
        }
    }

    /// Opens and connects again ([`reopen`]'s doubling waits) until the printer answers or the
    /// replug time is up.
    async fn reconnect(&mut self) -> Result<&mut Marlin<T>, MarlinError> {
        self.marlin = None;
        let limit = self.settings.replug_timeout;
        tracing::warn!(printer = %self.settings.name, "connection lost; waiting for the printer");
        let (open, settings) = (&mut self.open, &self.settings);
        let attempt = async || {
            let transport = open().await.map_err(Failure::from)?;
            Marlin::connect(transport, settings.clone())
                .await
                .map_err(Failure::from)
        };
        // An attempt still under way when the time is up is cut short.
        let last = match tokio::time::timeout(limit, reopen(limit, attempt)).await {
            Ok(Ok(marlin)) => {
                tracing::info!(printer = %self.settings.name, "reconnected");
                return Ok(self.marlin.insert(marlin));
            }
            Ok(Err(error)) => error,
            Err(elapsed) => Failure::from(elapsed),
        };
        Err(MarlinError::Unplugged {
            printer: self.settings.name.clone(),
            seconds: limit.as_secs_f64(),
            source: last,
        })
    }
}
