//! The [`Robotiq2f85`]'s `real` interface: the gripper through the Robotiq URCap's socket on
//! the UR controller (port 63352), activated at bind; a task sends each request and polls the
//! status.

use std::cell::Cell;
use std::rc::Rc;
use std::time::Duration;

use serde::Deserialize;
use tokio::net::TcpStream;
use tokio::sync::watch;
use yarok_core::component::{Bind, BindError, Interface};
use yarok_hw::robotiq::{Gripper, GripperError, GripperState, Motion};
use yarok_hw::{Real, connect_within, reopen};

use super::Robotiq2f85;
use crate::grippers::parallel::{FingerDrive, ParallelGripper, Request, Stroke};

/// How often the status is read.
const POLL: Duration = Duration::from_millis(20);

/// The interface settings of a real gripper (`[interfaces."/path/to/gripper"]`).
#[derive(Debug, Clone, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct Settings {
    /// The UR controller the gripper is wired to.
    host: String,
    /// The URCap's socket.
    port: u16,
    /// Seconds a reply may take (the URCap's socket answers within milliseconds): a gripper
    /// silent for longer ends the run, naming it.
    reply_seconds: f64,
    /// Seconds activation may take.
    activation_seconds: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            host: "192.168.1.10".into(),
            port: 63352,
            reply_seconds: 0.3,
            activation_seconds: 5.0,
        }
    }
}

/// What the driver's task knows of the real gripper, and the request it is to send.
struct RealFingers {
    status: Cell<GripperState>,
    requests: watch::Sender<Option<[u8; 3]>>,
}

impl FingerDrive for RealFingers {
    fn position(&self) -> f64 {
        f64::from(self.status.get().position)
    }

    /// Moving until the gripper reports the latest request as taken and its motion ended.
    fn is_moving(&self) -> bool {
        let status = self.status.get();
        let requested = self.requests.borrow().map(|[position, ..]| position);
        requested.is_some_and(|position| position != status.requested)
            || status.motion == Motion::Moving
    }

    fn requested(&self) -> Request {
        match *self.requests.borrow() {
            Some(request) => {
                let [position, speed, force] = request.map(f64::from);
                Request {
                    position,
                    speed,
                    force,
                }
            }
            None => Request::POWER_ON,
        }
    }

    fn request(&self, request: Request) {
        let bytes = [request.position, request.speed, request.force]
            .map(|value| value.round().clamp(0.0, 255.0) as u8);
        self.requests.send_replace(Some(bytes));
    }

    /// Stopped on an object (`OBJ` 1 or 2), as the gripper reports.
    fn object_detected(&self) -> bool {
        matches!(
            self.status.get().motion,
            Motion::ObjectWhileOpening | Motion::ObjectWhileClosing
        )
    }
}

impl Interface<Real> for Robotiq2f85 {
    fn check(bind: &Bind<Real>) -> Result<(), BindError> {
        bind.settings::<Settings>().map(drop)
    }

    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        let settings: Settings = bind.settings()?;
        let socket = Socket::new(&settings);
        let mut gripper = socket.open().await.map_err(|e| bind.error(e))?;
        gripper
            .activate(seconds(settings.activation_seconds))
            .await
            .map_err(|e| bind.error(e))?;
        let status = gripper.state().await.map_err(|e| bind.error(e))?;
        let fingers = Rc::new(RealFingers {
            status: Cell::new(status),
            requests: watch::Sender::new(None),
        });
        bind.spawn(drive(Rc::clone(&fingers), socket, gripper));
        Ok(Self(ParallelGripper::with_drive(
            bind,
            fingers,
            Stroke::ROBOTIQ_2F85,
        )))
    }
}

fn seconds(value: f64) -> Duration {
    Duration::try_from_secs_f64(value).unwrap_or_default()
}

/// Where the gripper's socket is, and how long its replies may take.
struct Socket {
    host: String,
    port: u16,
    name: String,
    reply: Duration,
}

impl Socket {
    fn new(settings: &Settings) -> Self {
        Self {
            host: settings.host.clone(),
            port: settings.port,
            name: format!("{}:{}", settings.host, settings.port),
            reply: seconds(settings.reply_seconds),
        }
    }

    /// A connection to the gripper, made within the reply time.
    async fn open(&self) -> Result<Gripper<TcpStream>, String> {
        let stream = connect_within(&self.host, self.port, self.reply)
            .await
            .map_err(|error| format!("gripper {}: {error}", self.name))?;
        Ok(Gripper::new(stream, self.name.clone(), self.reply))
    }

    /// The gripper reconnected after `dropped` (attempts within the reply time, waits doubling
    /// between them), still active; one that lost its activation is not activated again, since
    /// activating moves the fingers through their whole stroke.
    async fn reopen(
        &self,
        dropped: &GripperError,
    ) -> Result<Gripper<TcpStream>, yarok_core::BoxError> {
        tracing::warn!(gripper = %self.name, "connection lost ({dropped}); reconnecting");
        let reopened = reopen(self.reply, async || {
            let mut gripper = self.open().await?;
            let active = gripper.get("STA").await.map_err(|e| e.to_string())?;
            Ok::<_, String>((gripper, active))
        })
        .await;
        match reopened {
            Ok((gripper, 3)) => {
                tracing::info!(gripper = %self.name, "reconnected");
                Ok(gripper)
            }
            Ok((_, status)) => Err(format!(
                "{dropped}; reconnected, but the gripper is no longer active (STA {status}): it \
                 was reset, activate it again"
            )
            .into()),
            Err(failed) => Err(format!(
                "{dropped}; not back within {} s: {failed}",
                self.reply.as_secs_f64()
            )
            .into()),
        }
    }
}

/// Whether `error` is the connection failing (not the gripper answering with a fault, nor
/// falling silent on an open connection).
fn is_connection_lost(error: &GripperError) -> bool {
    matches!(error, GripperError::Closed { .. } | GripperError::Io { .. })
}

/// `error` as the run's end: a gripper that answers nothing on an open connection is named
/// silent at once, not reconnected (its connection is not what failed).
fn ended_by(error: GripperError) -> yarok_core::BoxError {
    match error {
        GripperError::Timeout { .. } => format!(
            "{error}: the gripper went silent (its connection is open, nothing answers): check \
             its cable and the Robotiq URCap on the controller"
        )
        .into(),
        other => other.into(),
    }
}

/// Sends each new request and reads the status every [`POLL`], reconnecting a dropped socket:
/// a request the connection dropped under is sent again only when the gripper shows it did not
/// take it. A fault ends the run with the gripper's error.
async fn drive(
    fingers: Rc<RealFingers>,
    socket: Socket,
    mut gripper: Gripper<TcpStream>,
) -> Result<(), yarok_core::BoxError> {
    let mut requests = fingers.requests.subscribe();
    let mut poll = tokio::time::interval(POLL);
    loop {
        tokio::select! {
            changed = requests.changed() => {
                if changed.is_err() {
                    return Ok(());
                }
                let request = *requests.borrow_and_update();
                if let Some([position, speed, force]) = request {
                    match gripper.go_to(position, speed, force).await {
                        Err(lost) if is_connection_lost(&lost) => {
                            gripper = socket.reopen(&lost).await?;
                            let taken = gripper.get("PRE").await? == position;
                            if !taken {
                                tracing::warn!(
                                    gripper = %socket.name,
                                    "the move to {position} was lost with the connection; sending it again"
                                );
                                gripper.go_to(position, speed, force).await?;
                            }
                        }
                        other => other.map_err(ended_by)?,
                    }
                }
            }
            _ = poll.tick() => {
                let status = async {
                    gripper.check_fault().await?;
                    gripper.state().await
                };
                match status.await {
                    Ok(status) => fingers.status.set(status),
                    Err(lost) if is_connection_lost(&lost) => {
                        gripper = socket.reopen(&lost).await?;
                    }
                    Err(other) => return Err(ended_by(other)),
                }
            }
        }
    }
}
