//! A scripted Marlin printer for tests: it expects the driver's lines byte for byte and sends
//! its replies, over any async stream (an in-memory pipe, a pseudo-terminal's other side).
//! Shared by yarok-hw's tests and the workspace's, each using part of it.

use std::time::Duration;

use tokio::io::{AsyncBufReadExt, AsyncRead, AsyncWrite, AsyncWriteExt, BufReader};

/// One step of a scripted printer.
#[derive(Debug, Clone, Copy)]
pub enum Step {
    /// The next line the driver must send, byte for byte (without the newline).
    Expect(&'static str),
    /// Lines the printer sends.
    Send(&'static [&'static str]),
    /// Raw bytes the printer sends.
    Bytes(&'static [u8]),
    /// Seconds the printer lets pass.
    Sleep(f64),
    /// The printer goes away.
    Close,
}

/// Plays `script` as the printer on `io`; panics (failing the test) on an unexpected line.
pub async fn printer<Io: AsyncRead + AsyncWrite + Unpin>(io: Io, script: Vec<Step>) {
    let mut io = BufReader::new(io);
    for step in script {
        match step {
            Step::Expect(expected) => {
                let mut line = String::new();
                io.read_line(&mut line).await.unwrap();
                assert_eq!(line, format!("{expected}\n"), "the driver sent");
            }
            Step::Send(lines) => {
                for line in lines {
                    io.get_mut()
                        .write_all(format!("{line}\n").as_bytes())
                        .await
                        .unwrap();
                }
            }
            Step::Bytes(bytes) => io.get_mut().write_all(bytes).await.unwrap(),
            Step::Sleep(seconds) => tokio::time::sleep(Duration::from_secs_f64(seconds)).await,
            Step::Close => return,
        }
    }
    // Keep the line open until the driver is done with it.
    let mut rest = String::new();
    let _ = io.read_line(&mut rest).await;
}

/// A pseudo-terminal: the path of its device side, and its other side as an async stream.
pub fn pseudo_terminal() -> (
    String,
    nix::pty::OpenptyResult,
    impl AsyncRead + AsyncWrite + Unpin,
) {
    use nix::fcntl::{FcntlArg, OFlag, fcntl};
    use std::os::fd::AsRawFd;
    let pty = nix::pty::openpty(None, None).unwrap();
    // Raw from the start, as a device is: no echo of what the printer sends before the port
    // is opened.
    let mut raw = nix::sys::termios::tcgetattr(&pty.slave).unwrap();
    nix::sys::termios::cfmakeraw(&mut raw);
    nix::sys::termios::tcsetattr(&pty.slave, nix::sys::termios::SetArg::TCSANOW, &raw).unwrap();
    fcntl(
        &pty.master,
        FcntlArg::F_SETFL(OFlag::O_RDWR | OFlag::O_NONBLOCK),
    )
    .unwrap();
    let path = std::fs::read_link(format!("/proc/self/fd/{}", pty.slave.as_raw_fd()))
        .unwrap()
        .display()
        .to_string();
    let reader =
        tokio::net::unix::pipe::Receiver::from_owned_fd_unchecked(pty.master.try_clone().unwrap())
            .unwrap();
    let writer =
        tokio::net::unix::pipe::Sender::from_owned_fd_unchecked(pty.master.try_clone().unwrap())
            .unwrap();
    (path, pty, tokio::io::join(reader, writer))
}
