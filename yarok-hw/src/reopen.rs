//! [`reopen`]: a dropped connection made again, with waits that double between attempts.

use std::time::Duration;

use tokio::time::Instant;

/// The first wait between attempts; it doubles after each failed attempt.
pub const FIRST_RETRY: Duration = Duration::from_millis(100);

/// The connection `open` makes, tried at once and then again after waits doubling from
/// [`FIRST_RETRY`], as long as an attempt can start within `window`; or the last attempt's
/// error. Each attempt is bounded only by `open`'s own time limits, so a peer that accepts and
/// then stays silent costs one attempt, not a tight loop of them.
///
/// ```
/// # async fn run() {
/// use std::time::Duration;
///
/// let mut attempts = 0;
/// let opened = yarok_hw::reopen(Duration::from_secs(1), async || {
///     attempts += 1;
///     if attempts < 3 { Err("refused") } else { Ok("connected") }
/// })
/// .await;
/// assert_eq!(opened, Ok("connected"));
/// # }
/// ```
///
/// # Errors
///
/// The last attempt's error, when none succeeded within `window`.
pub async fn reopen<T, E>(
    window: Duration,
    mut open: impl AsyncFnMut() -> Result<T, E>,
) -> Result<T, E> {
    let until = Instant::now() + window;
    let mut wait = FIRST_RETRY;
    loop {
        let failed = match open().await {
            Ok(connection) => return Ok(connection),
            Err(error) => error,
        };
        if Instant::now() + wait >= until {
            return Err(failed);
        }
        tokio::time::sleep(wait).await;
        wait *= 2;
    }
}
