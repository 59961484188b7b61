//! Waits on a recorder's helper (an encoder process, a writing thread) that end after a bound,
//! so that a helper which stops keeping up ends the run with an error instead of blocking it.

use std::sync::mpsc::{SyncSender, TrySendError};
use std::time::{Duration, Instant};

/// How often a bounded wait looks again.
const POLL: Duration = Duration::from_millis(5);

/// Why a queue refused an item.
#[derive(Debug, PartialEq, Eq)]
pub(super) enum Refused {
    /// The queue stayed full for the whole wait.
    Full,
    /// Nothing reads the queue any more.
    Gone,
}

/// Queues `item`, waiting at most `within` for room.
pub(super) fn send_within<T>(
    queue: &SyncSender<T>,
    item: T,
    within: Duration,
) -> Result<(), Refused> {
    let until = Instant::now() + within;
    let mut item = item;
    loop {
        match queue.try_send(item) {
            Ok(()) => return Ok(()),
            Err(TrySendError::Full(again)) if Instant::now() < until => {
                item = again;
                std::thread::sleep(POLL);
            }
            Err(TrySendError::Full(_)) => return Err(Refused::Full),
            Err(TrySendError::Disconnected(_)) => return Err(Refused::Gone),
        }
    }
}

/// Looks at `done` until it gives a value or `within` has passed.
pub(super) fn poll_within<T>(
    within: Duration,
    mut done: impl FnMut() -> Result<Option<T>, std::io::Error>,
) -> Result<Option<T>, std::io::Error> {
    let until = Instant::now() + within;
    loop {
        if let Some(value) = done()? {
            return Ok(Some(value));
        }
        if Instant::now() >= until {
            return Ok(None);
        }
        std::thread::sleep(POLL);
    }
}

#[cfg(test)]
mod tests {
    use std::sync::mpsc::sync_channel;

    use super::*;

    #[test]
    fn a_full_queue_is_refused_after_the_wait_and_a_closed_one_at_once() {
        let (queue, reader) = sync_channel(1);
        assert_eq!(send_within(&queue, 1, Duration::ZERO), Ok(()));
        let started = Instant::now();
        assert_eq!(
            send_within(&queue, 2, Duration::from_millis(30)),
            Err(Refused::Full)
        );
        assert!(started.elapsed() >= Duration::from_millis(30));
        drop(reader);
        assert_eq!(
            send_within(&queue, 3, Duration::from_secs(60)),
            Err(Refused::Gone)
        );
    }

    #[test]
    fn polling_gives_the_value_or_none_after_the_wait() {
        let mut looks = 0;
        let found = poll_within(Duration::from_secs(60), || {
            looks += 1;
            Ok((looks == 3).then_some(looks))
        });
        assert_eq!(found.unwrap(), Some(3));
        let never = poll_within::<()>(Duration::from_millis(20), || Ok(None));
        assert_eq!(never.unwrap(), None);
    }
}
