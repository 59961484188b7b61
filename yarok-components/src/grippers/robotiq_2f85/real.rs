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
use yarok_hw::Real;
use yarok_hw::robotiq::{Gripper, GripperState, Motion};

use super::{Drive, Robotiq2f85};

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
    /// Seconds a reply may take.
    reply_seconds: f64,
    /// Seconds activation may take.
    activation_seconds: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            host: "192.168.1.10".into(),
            port: 63352,
            reply_seconds: 1.0,
            activation_seconds: 5.0,
        }
    }
}

/// What the driver's task knows of the real gripper, and the request it is to send.
pub(super) struct RealFingers {
    status: Cell<GripperState>,
    requests: watch::Sender<Option<[u8; 3]>>,
}

impl RealFingers {
    pub(super) fn position(&self) -> u8 {
        self.status.get().position
    }

    pub(super) fn request(&self, request: [u8; 3]) {
        self.requests.send_replace(Some(request));
    }

    /// Moving until the gripper reports the latest request as taken and its motion ended.
    pub(super) fn is_moving(&self) -> bool {
        let status = self.status.get();
        let requested = self.requests.borrow().map(|[position, ..]| position);
        requested.is_some_and(|position| position != status.requested)
            || status.motion == Motion::Moving
    }

    /// Stopped on an object (`OBJ` 1 or 2).
    pub(super) fn object_detected(&self) -> bool {
        matches!(
            self.status.get().motion,
            Motion::ObjectWhileOpening | Motion::ObjectWhileClosing
        )
    }
}

impl Interface<Real> for Robotiq2f85 {
    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        let settings: Settings = bind.settings()?;
        let seconds = |value: f64| Duration::try_from_secs_f64(value).unwrap_or_default();
        let address = (settings.host.as_str(), settings.port);
        let name = format!("{}:{}", settings.host, settings.port);
        let stream = bind
            .within(
                settings.reply_seconds,
                "the gripper's connection",
                TcpStream::connect(address),
            )
            .await?
            .map_err(|e| bind.error(format!("gripper {name}: {e}")))?;
        let mut gripper = Gripper::new(stream, name, seconds(settings.reply_seconds));
        gripper
            .activate(seconds(settings.activation_seconds))
            .await
            .map_err(|e| bind.error(e))?;
        let status = gripper.state().await.map_err(|e| bind.error(e))?;
        let fingers = Rc::new(RealFingers {
            status: Cell::new(status),
            requests: watch::Sender::new(None),
        });
        bind.spawn(drive(Rc::clone(&fingers), gripper));
        Ok(Self::with_drive(bind, Drive::Real(fingers)))
    }
}

/// Sends each new request and reads the status every [`POLL`]; a fault ends the run with the
/// gripper's error.
async fn drive(
    fingers: Rc<RealFingers>,
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
                    gripper.go_to(position, speed, force).await?;
                }
            }
            _ = poll.tick() => {
                gripper.check_fault().await?;
                fingers.status.set(gripper.state().await?);
            }
        }
    }
}
