//! [`SerialPort`]: a serial device or pseudo-terminal as an async byte stream, in raw mode at a
//! baud rate.

use std::os::unix::fs::OpenOptionsExt;
use std::pin::Pin;
use std::task::{Context, Poll};

use nix::sys::termios::{self, BaudRate, ControlFlags, SetArg};
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::unix::pipe;

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
    /// The device is not a terminal, or refused the settings.
    #[error("serial port {path}: cannot set it up: {source}")]
    Setup {
        /// The device.
        path: String,
        /// Why.
        source: nix::Error,
    },
    /// The baud rate is not one the terminal interface offers.
    #[error("serial port {path}: {baud} baud is not a standard rate (9600 … 1000000)")]
    Baud {
        /// The device.
        path: String,
        /// The rate asked for.
        baud: u32,
    },
}

/// A serial port (a USB-serial printer board, or a pseudo-terminal) in raw mode: 8 data bits,
/// no parity, no flow control, no echo, no line editing; reads and writes never block the
/// thread. Opening it asserts DTR, which resets many printer boards.
///
/// ```no_run
/// # async fn run() -> Result<(), Box<dyn std::error::Error>> {
/// use yarok_hw::SerialPort;
/// use yarok_hw::marlin::{Marlin, MarlinSettings};
///
/// let port = SerialPort::open("/dev/ttyUSB0", 115_200)?;
/// let mut printer = Marlin::connect(port, MarlinSettings::new("/dev/ttyUSB0")).await?;
/// printer.home().await?;
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct SerialPort {
    // The device opened twice, each half registered with tokio's reactor as a stream (a
    // terminal polls like a pipe).
    reader: pipe::Receiver,
    writer: pipe::Sender,
}

impl SerialPort {
    /// Opens `path` at `baud` bits a second, in raw mode. Call it inside a tokio runtime.
    ///
    /// # Errors
    ///
    /// [`SerialError`] naming the device.
    pub fn open(path: &str, baud: u32) -> Result<Self, SerialError> {
        let rate = baud_rate(baud).ok_or_else(|| SerialError::Baud {
            path: path.to_owned(),
            baud,
        })?;
        let open = |source| SerialError::Open {
            path: path.to_owned(),
            source,
        };
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .custom_flags(nix::libc::O_NOCTTY | nix::libc::O_NONBLOCK)
            .open(path)
            .map_err(open)?;
        let setup = |source| SerialError::Setup {
            path: path.to_owned(),
            source,
        };
        let mut settings = termios::tcgetattr(&file).map_err(setup)?;
        termios::cfmakeraw(&mut settings);
        settings.control_flags |= ControlFlags::CLOCAL | ControlFlags::CREAD;
        termios::cfsetspeed(&mut settings, rate).map_err(setup)?;
        termios::tcsetattr(&file, SetArg::TCSANOW, &settings).map_err(setup)?;
        let reader = file.try_clone().map_err(open)?;
        Ok(Self {
            reader: pipe::Receiver::from_file_unchecked(reader).map_err(open)?,
            writer: pipe::Sender::from_file_unchecked(file).map_err(open)?,
        })
    }
}

/// The terminal interface's constant for `baud`, if it has one.
fn baud_rate(baud: u32) -> Option<BaudRate> {
    Some(match baud {
        9_600 => BaudRate::B9600,
        19_200 => BaudRate::B19200,
        38_400 => BaudRate::B38400,
        57_600 => BaudRate::B57600,
        115_200 => BaudRate::B115200,
        230_400 => BaudRate::B230400,
        460_800 => BaudRate::B460800,
        500_000 => BaudRate::B500000,
        921_600 => BaudRate::B921600,
        1_000_000 => BaudRate::B1000000,
        _ => return None,
    })
}

impl AsyncRead for SerialPort {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<std::io::Result<()>> {
        match Pin::new(&mut self.reader).poll_read(cx, buf) {
            // A pseudo-terminal whose other side closed reads EIO: the end of the stream.
            Poll::Ready(Err(error)) if error.raw_os_error() == Some(nix::libc::EIO) => {
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
        Pin::new(&mut self.writer).poll_write(cx, bytes)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.writer).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.writer).poll_shutdown(cx)
    }
}
