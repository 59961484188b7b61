//! Reading from devices that may send anything, by a deadline: whole lines ([`line_by`]) and
//! more bytes for a framed protocol ([`read_more`]). Both are cancel safe: what was read stays
//! in the caller's buffer for the next call.

use tokio::io::{AsyncBufRead, AsyncBufReadExt, AsyncRead, AsyncReadExt};
use tokio::time::Instant;

/// Why a read by a deadline gave nothing; each driver names it in its own error.
#[derive(Debug)]
pub(crate) enum Unread {
    /// The stream ended.
    Closed,
    /// Reading failed.
    Failed(std::io::Error),
    /// The deadline passed.
    TimedOut,
}

/// The next line from `reader` by `deadline`, without its ending (`\n` or `\r\n`), lossily
/// decoded and cut at `max` bytes (the rest of a longer line is dropped). A partly read line
/// stays in `partial`.
pub(crate) async fn line_by<R: AsyncBufRead + Unpin>(
    reader: &mut R,
    partial: &mut Vec<u8>,
    max: usize,
    deadline: Instant,
) -> Result<String, Unread> {
    match tokio::time::timeout_at(deadline, read_line(reader, partial, max)).await {
        Ok(Ok(Some(line))) => Ok(line),
        Ok(Ok(None)) => Err(Unread::Closed),
        Ok(Err(source)) => Err(Unread::Failed(source)),
        Err(_) => Err(Unread::TimedOut),
    }
}

/// [`line_by`] without a deadline: `None` at the end of the stream.
pub(crate) async fn read_line<R: AsyncBufRead + Unpin>(
    reader: &mut R,
    partial: &mut Vec<u8>,
    max: usize,
) -> std::io::Result<Option<String>> {
    loop {
        let available = reader.fill_buf().await?;
        if available.is_empty() {
            return Ok(None);
        }
        let (taken, ended) = match available.iter().position(|b| *b == b'\n') {
            Some(end) => (end + 1, true),
            None => (available.len(), false),
        };
        let room = max.saturating_sub(partial.len());
        partial.extend_from_slice(&available[..taken.min(room)]);
        reader.consume(taken);
        if ended {
            let line = String::from_utf8_lossy(partial)
                .trim_end_matches(['\r', '\n'])
                .to_owned();
            partial.clear();
            return Ok(Some(line));
        }
    }
}

/// Appends what `stream` has next to `buffer`, by `deadline`.
pub(crate) async fn read_more<R: AsyncRead + Unpin>(
    stream: &mut R,
    buffer: &mut Vec<u8>,
    deadline: Instant,
) -> Result<(), Unread> {
    buffer.reserve(4096);
    match tokio::time::timeout_at(deadline, stream.read_buf(buffer)).await {
        Ok(Ok(0)) => Err(Unread::Closed),
        Ok(Ok(_)) => Ok(()),
        Ok(Err(source)) => Err(Unread::Failed(source)),
        Err(_) => Err(Unread::TimedOut),
    }
}
