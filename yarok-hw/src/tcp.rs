//! [`connect_within`]: a TCP connection to a device, made within a time limit.

use std::time::Duration;

use tokio::net::TcpStream;

/// Why a connection was not made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ConnectError {
    /// The connection was refused or failed.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// Nothing answered within the limit.
    #[error("no connection within {} s", .0.as_secs_f64())]
    Timeout(Duration),
}

/// A connection to `host`'s `port`, made within `within` (a host that does not answer, as an
/// unplugged controller does not, costs that long and no more).
///
/// ```no_run
/// # async fn run() -> Result<(), yarok_hw::ConnectError> {
/// use std::time::Duration;
///
/// let stream = yarok_hw::connect_within("192.168.1.10", 29999, Duration::from_secs(1)).await?;
/// # Ok(()) }
/// ```
///
/// # Errors
///
/// [`ConnectError`]: the connection's own error, or the time running out.
pub async fn connect_within(
    host: &str,
    port: u16,
    within: Duration,
) -> Result<TcpStream, ConnectError> {
    match tokio::time::timeout(within, TcpStream::connect((host, port))).await {
        Ok(connected) => Ok(connected?),
        Err(_) => Err(ConnectError::Timeout(within)),
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::{ConnectError, connect_within};

    #[tokio::test]
    async fn a_listening_port_connects_and_a_closed_one_is_refused() {
        let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let port = listener.local_addr().unwrap().port();
        let limit = Duration::from_secs(5);
        connect_within("127.0.0.1", port, limit).await.unwrap();
        drop(listener);
        let refused = connect_within("127.0.0.1", port, limit).await.unwrap_err();
        assert!(matches!(refused, ConnectError::Io(_)), "{refused}");
    }

    #[test]
    fn the_time_limit_is_named_in_seconds() {
        let error = ConnectError::Timeout(Duration::from_millis(1500));
        assert_eq!(error.to_string(), "no connection within 1.5 s");
    }
}
