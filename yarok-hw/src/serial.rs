//! [`SerialPort`]: a serial device or pseudo-terminal as an async byte stream, in raw mode at any
//! baud rate the device takes.

use std::pin::Pin;
use std::task::{Context, Poll};

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio_serial::{DataBits, FlowControl, Parity, SerialPortBuilderExt, SerialStream, StopBits};

/// A serial port could not be opened or set up.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SerialError {
    /// The device could not be opened (missing, busy, no permission).
    #[error("serial port {path}: {source}")]
    Open {
        /// The device.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// The device is not a terminal, or refused the settings (the baud rate among them).
    #[error("serial port {path}: cannot set it up at {baud} baud: {source}")]
    Setup {
        /// The device.
        path: String,
        /// The rate asked for.
        baud: u32,
        /// Why.
        source: std::io::Error,
    },
}

/// A serial port (a USB-serial printer board, or a pseudo-terminal) in raw mode: 8 data bits,
/// no parity, one stop bit, no flow control, no echo, no line editing; reads and writes never
/// block the thread. Any baud rate the device takes works, standard or not (Marlin's 250000 and
/// 500000 among them: on Linux the kernel's arbitrary-rate interface sets the exact rate). The
/// port is opened exclusively, so a second program cannot interleave its own commands. Opening
/// it asserts DTR, which resets many printer boards.
///
/// ```no_run
/// # async fn run() -> Result<(), Box<dyn std::error::Error>> {
/// use yarok_hw::SerialPort;
/// use yarok_hw::marlin::{Marlin, MarlinSettings};
///
/// let port = SerialPort::open("/dev/ttyUSB0", 250_000)?;
/// let mut printer = Marlin::connect(port, MarlinSettings::new("/dev/ttyUSB0")).await?;
/// printer.home().await?;
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct SerialPort {
    stream: SerialStream,
}

impl SerialPort {
    /// Opens `path` at `baud` bits a second, in raw mode. Call it inside a tokio runtime.
    ///
    /// # Errors
    ///
    /// [`SerialError`] naming the device: [`SerialError::Open`] if it cannot be opened,
    /// [`SerialError::Setup`] if it is not a terminal or refuses the settings.
    pub fn open(path: &str, baud: u32) -> Result<Self, SerialError> {
        let stream = tokio_serial::new(path, baud)
            .data_bits(DataBits::Eight)
            .parity(Parity::None)
            .stop_bits(StopBits::One)
            .flow_control(FlowControl::None)
            .dtr_on_open(true)
            .open_native_async()
            .map_err(|error| {
                let opening = matches!(
                    error.kind(),
                    tokio_serial::ErrorKind::NoDevice
                        | tokio_serial::ErrorKind::Io(
                            std::io::ErrorKind::NotFound | std::io::ErrorKind::PermissionDenied
                        )
                );
                let (path, source) = (path.to_owned(), std::io::Error::from(error));
                if opening {
                    SerialError::Open { path, source }
                } else {
                    SerialError::Setup { path, baud, source }
                }
            })?;
        Ok(Self { stream })
    }
}

impl AsyncRead for SerialPort {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<std::io::Result<()>> {
        match Pin::new(&mut self.stream).poll_read(cx, buf) {
            // A pseudo-terminal whose other side closed reads EIO: the end of the stream.
            Poll::Ready(Err(error)) if error.raw_os_error() == Some(libc::EIO) => {
                Poll::Ready(Ok(()))
            }
            other => other,
        }
    }
}

impl AsyncWrite for SerialPort {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bytes: &[u8],
    ) -> Poll<std::io::Result<usize>> {
        Pin::new(&mut self.stream).poll_write(cx, bytes)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.stream).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.stream).poll_shutdown(cx)
    }
}
