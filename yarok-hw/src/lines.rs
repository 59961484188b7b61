//! Reading text lines from devices that may send anything: [`read_line`].

use tokio::io::{AsyncBufRead, AsyncBufReadExt};

/// The next line from `reader`, without its ending (`\n` or `\r\n`), lossily decoded and cut at
/// `max` bytes (the rest of a longer line is dropped); `None` at the end of the stream.
///
/// Cancel safe: a partly read line stays in `partial` for the next call.
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
