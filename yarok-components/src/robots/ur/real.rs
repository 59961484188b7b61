//! The UR arms' `real` interface: the controller's RTDE stream (joints, speeds, safety) and
//! its secondary interface (URScript `movej`/`movel`/`stopj`), with the robot's kinematics
//! checked at connect and the RTDE stream reconnected when it drops. A stream of targets runs
//! as one program on the controller ([`external_control`]) that connects back to a port this
//! side listens on, with a watchdog that stops the arm when the targets stop coming.

use std::cell::{Cell, RefCell};
use std::collections::VecDeque;
use std::future::Future;
use std::pin::Pin;
use std::rc::Rc;
use std::time::Duration;

use serde::Deserialize;
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{Notify, oneshot};
use tokio::time::Instant;
use yarok_core::component::{Bind, BindError};
use yarok_core::time::Clock;
use yarok_hw::ur::dashboard::{Dashboard, RobotMode, SafetyStatus};
use yarok_hw::ur::external_control::{self, ExternalControl, ProgramSettings};
use yarok_hw::ur::rtde::{Rtde, RtdeError, RtdeSettings, Value};
use yarok_hw::ur::script;
use yarok_hw::ur::secondary::{KinematicsInfo, Secondary, send_script_and_close};
use yarok_hw::{Real, connect_within, reopen};

use super::drive::{ArmDrive, Order, Setpoint};
use super::error::MotionError;
use super::kinematics::{DhParameters, Joints, Kinematics, pose_to_vector};
use super::payload::Payload;
use super::streaming::UR_JOINT_ACCELERATION;

const RTDE_PORT: u16 = 30004;
const SECONDARY_PORT: u16 = 30002;
const DASHBOARD_PORT: u16 = 29999;

/// How long the stop's connection waits, once `stopj` is sent, for the controller to close it.
const STOP_LINGER: Duration = Duration::from_millis(250);

/// `servoj`'s smoothing of a streamed target (seconds) and its gain: URScript's defaults.
const SERVO_LOOKAHEAD_S: f64 = 0.1;
const SERVO_GAIN: f64 = 300.0;

/// How long after the streaming program ended its end is reported as its own: RTDE (a
/// package every 2 or 8 ms) has by then said whether a safety stop or the power ended it.
const PROGRAM_END_CONFIRMED_AFTER: Duration = Duration::from_millis(50);

/// How many keep-alives the streaming program gets within its watchdog time.
const KEEP_ALIVES_PER_WATCHDOG: u32 = 4;

/// What the arm streams over RTDE, in this order.
const OUTPUTS: [&str; 4] = ["actual_q", "actual_qd", "robot_mode", "safety_mode"];

/// How long after RTDE's last data package the joints are taken as stale: a stream at 125 Hz
/// or more sends one every 8 ms.
const STALE_AFTER: Duration = Duration::from_millis(100);

/// Seconds the arm's stream may take to show an unlocked protective stop cleared.
const UNLOCKED_SECONDS: f64 = 2.0;

/// How far (metres) a DH length may differ from the configured one: calibration moves them by
/// well under this, another model by centimetres.
const DH_TOLERANCE: f64 = 5e-3;

/// The interface settings of a real UR arm (`[interfaces."/path/to/arm"]`).
#[derive(Debug, Clone, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct Settings {
    /// The controller's address.
    host: String,
    /// RTDE packages a second; the controller's most (125 on CB3, 500 on e-Series) when unset.
    rtde_hz: Option<f64>,
    /// Seconds a reply may take, and a dropped RTDE stream may take to come back.
    reply_seconds: f64,
    /// Seconds the first connection may take.
    connect_seconds: f64,
    /// The payload: its mass (kg) and centre of gravity (m, in the flange frame), set on the
    /// controller at connect; the controller's own setting when unset.
    payload: Option<[f64; 4]>,
    /// The port the streaming program connects back to (0: any free one).
    reverse_port: u16,
    /// The address the controller reaches this computer at; by default the one this computer
    /// reaches the controller from.
    reverse_host: Option<String>,
    /// Seconds the streaming program waits for the next target (or keep-alive) before it
    /// stops the arm.
    watchdog_seconds: f64,
}

/// A real arm's interface settings, read and checked.
pub(super) struct CheckedSettings {
    settings: Settings,
    payload: Option<Payload>,
}

/// The arm's interface settings, checked without touching the controller.
pub(super) fn settings(bind: &Bind<Real>) -> Result<CheckedSettings, BindError> {
    let settings: Settings = bind.settings()?;
    if !(settings.watchdog_seconds.is_finite()
        && (0.01..=10.0).contains(&settings.watchdog_seconds))
    {
        return Err(bind.error(format!(
            "watchdog_seconds is {}: give the seconds the streaming program waits for the next \
             target before it stops the arm, 0.01 to 10",
            settings.watchdog_seconds
        )));
    }
    let payload = settings
        .payload
        .map(|[mass, x, y, z]| Payload::new(mass, [x, y, z]))
        .transpose()
        .map_err(|e| bind.error(e))?;
    Ok(CheckedSettings { settings, payload })
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            host: "192.168.1.10".into(),
            rtde_hz: None,
            reply_seconds: 2.0,
            connect_seconds: 5.0,
            payload: None,
            reverse_port: 50002,
            reverse_host: None,
            watchdog_seconds: 0.2,
        }
    }
}

/// Safety modes as RTDE numbers them; 1 and 2 let the arm move.
fn safety_mode_name(mode: i32) -> &'static str {
    match mode {
        1 => "NORMAL",
        2 => "REDUCED",
        3 => "PROTECTIVE_STOP",
        4 => "RECOVERY",
        5 => "SAFEGUARD_STOP",
        6 => "SYSTEM_EMERGENCY_STOP",
        7 => "ROBOT_EMERGENCY_STOP",
        8 => "VIOLATION",
        9 => "FAULT",
        _ => "UNKNOWN",
    }
}

/// Robot modes as RTDE numbers them; 7 lets the arm move.
fn robot_mode_name(mode: i32) -> &'static str {
    match mode {
        -1 => "NO_CONTROLLER",
        0 => "DISCONNECTED",
        1 => "CONFIRM_SAFETY",
        2 => "BOOTING",
        3 => "POWER_OFF",
        4 => "POWER_ON",
        5 => "IDLE",
        6 => "BACKDRIVE",
        7 => "RUNNING",
        8 => "UPDATING_FIRMWARE",
        _ => "UNKNOWN",
    }
}

/// The arm as RTDE last reported it.
#[derive(Debug, Clone, Copy)]
struct Measured {
    q: Joints,
    qd: Joints,
    robot_mode: i32,
    safety_mode: i32,
}

/// What the arm's driver task is asked to do.
enum Request {
    Script(String),
    /// A streamed target: only the latest is sent, never a queue of stale ones.
    Servo {
        target: Joints,
        seconds: f64,
        max_speed: Joints,
    },
    UnlockProtectiveStop(oneshot::Sender<Result<(), String>>),
}

/// The link between the controller's motions and the driver's task: the arm's drive in
/// `real`.
pub(super) struct RealLink {
    measured: Cell<Measured>,
    received_at: Cell<Instant>,
    /// A connection that dropped and was reopened since the last order was sent: what, and
    /// why.
    dropped_since_order: RefCell<Option<String>>,
    requests: RefCell<VecDeque<Request>>,
    wake: Notify,
    clock: Clock,
    /// Why the streaming program ended while streaming, and when this side saw it, until the
    /// stream is re-armed.
    program_ended: RefCell<Option<(String, Instant)>>,
}

impl RealLink {
    /// The safety mode's name when it stops the arm (a protective stop, an emergency stop, …).
    fn safety_stop(&self) -> Option<&'static str> {
        let mode = self.measured.get().safety_mode;
        (mode > 2).then(|| safety_mode_name(mode))
    }

    fn update(&self, now: Measured) {
        self.measured.set(now);
        self.received_at.set(Instant::now());
    }

    /// Notes that a connection dropped (`what`, and why): a motion under way may be lost.
    fn dropped(&self, what: String) {
        *self.dropped_since_order.borrow_mut() = Some(what);
    }

    fn request(&self, request: Request) {
        let mut requests = self.requests.borrow_mut();
        if matches!(request, Request::Servo { .. }) {
            requests.retain(|queued| !matches!(queued, Request::Servo { .. }));
        }
        requests.push_back(request);
        drop(requests);
        self.wake.notify_one();
    }
}

impl ArmDrive for RealLink {
    fn q(&self, _commanded: &Setpoint) -> Joints {
        self.measured.get().q
    }

    fn qd(&self, _commanded: &Setpoint) -> Joints {
        self.measured.get().qd
    }

    /// Sends the order's URScript to the controller, which runs it at once.
    fn order(&self, order: Order) {
        let script = match order {
            Order::MoveJ {
                target,
                speed,
                acceleration,
            } => script::movej(&target, speed, acceleration),
            Order::MoveL {
                pose,
                tcp,
                speed,
                acceleration,
            } => script::movel_with_tcp(
                &pose_to_vector(&pose),
                &pose_to_vector(&tcp),
                speed,
                acceleration,
            ),
            Order::ServoJ {
                target,
                seconds,
                max_speed,
            } => {
                self.dropped_since_order.take();
                self.request(Request::Servo {
                    target,
                    seconds,
                    max_speed,
                });
                return;
            }
            Order::StopJ { deceleration } => script::stopj(deceleration),
            Order::StopL { deceleration } => script::stopl(deceleration),
            Order::SetPayload(payload) => script::set_payload(payload.mass, payload.centre),
        };
        self.dropped_since_order.take();
        self.request(Request::Script(script));
    }

    /// Why the arm cannot move, if it cannot: its safety system stopped it, it is not
    /// running (powered off, brakes locked, …), or the streaming program ended.
    fn halt(&self) -> Option<MotionError> {
        let robot_mode = self.measured.get().robot_mode;
        if let Some(mode) = self.safety_stop() {
            return Some(MotionError::SafetyStop { mode });
        }
        if robot_mode != 7 {
            return Some(MotionError::NotRunning {
                mode: robot_mode_name(robot_mode),
            });
        }
        // A safety stop ends the program too, and RTDE may say so a package later: the end
        // is named as the program's own once RTDE had time to name another cause.
        let ended = self.program_ended.borrow().clone();
        ended
            .filter(|(_, seen)| seen.elapsed() >= PROGRAM_END_CONFIRMED_AFTER)
            .map(|(why, _)| MotionError::ProgramStopped { why })
    }

    fn rearm(&self) {
        self.program_ended.take();
    }

    fn interruption(&self) -> Option<String> {
        self.dropped_since_order.borrow().clone()
    }

    /// Whether RTDE has been heard from lately (a dropped stream being reconnected is not):
    /// else the joints are not where the arm is now.
    fn is_current(&self) -> bool {
        self.received_at.get().elapsed() <= STALE_AFTER
    }

    /// Unlocks a protective stop through the dashboard, and waits until the arm's own stream
    /// shows the stop cleared.
    fn unlock_protective_stop(&self) -> Pin<Box<dyn Future<Output = Result<(), String>> + '_>> {
        Box::pin(async move {
            let (reply, replied) = oneshot::channel();
            self.request(Request::UnlockProtectiveStop(reply));
            replied
                .await
                .unwrap_or_else(|_| Err("the arm's driver has stopped".into()))?;
            self.clock
                .wait(|| self.safety_stop().is_none())
                .timeout(UNLOCKED_SECONDS)
                .await
                .map_err(|e| format!("the safety stop did not clear: {e}"))
        })
    }
}

/// Which known arm DH parameters these are.
fn model_name(dh: &DhParameters) -> &'static str {
    let close = |known: &DhParameters| {
        [
            (dh.d1, known.d1),
            (dh.a2, known.a2),
            (dh.a3, known.a3),
            (dh.d4, known.d4),
            (dh.d5, known.d5),
            (dh.d6, known.d6),
        ]
        .iter()
        .all(|(a, b)| (a - b).abs() <= DH_TOLERANCE)
    };
    if close(&DhParameters::UR5) {
        "a UR5"
    } else if close(&DhParameters::UR5E) {
        "a UR5e"
    } else {
        "another arm"
    }
}

/// Refuses a controller whose arm's kinematics are not the configured ones.
fn check_kinematics(
    bind: &Bind<Real>,
    configured: &DhParameters,
    reported: &KinematicsInfo,
) -> Result<(), BindError> {
    let (a, d) = (reported.dh_a, reported.dh_d);
    let robot = DhParameters {
        d1: d[0],
        a2: a[1],
        a3: a[2],
        d4: d[3],
        d5: d[4],
        d6: d[5],
    };
    if model_name(&robot) == model_name(configured) && model_name(configured) != "another arm" {
        return Ok(());
    }
    let describe = |dh: &DhParameters| {
        format!(
            "{} (d1 {:.4}, a2 {:.4}, a3 {:.5}, d4 {:.4}, d5 {:.4}, d6 {:.4} m)",
            model_name(dh),
            dh.d1,
            dh.a2,
            dh.a3,
            dh.d4,
            dh.d5,
            dh.d6
        )
    };
    Err(bind.error(format!(
        "the controller's arm is {}, but this component is {}",
        describe(&robot),
        describe(configured)
    )))
}

/// The dashboard of `host`, connected and its welcome read, each within `reply`.
async fn dashboard(
    host: &str,
    reply: Duration,
) -> Result<Dashboard<TcpStream>, yarok_core::BoxError> {
    let stream = connect_within(host, DASHBOARD_PORT, reply).await?;
    Ok(Dashboard::connect(stream, host, reply).await?)
}

/// Connects to RTDE at `host`, sets up the arm's outputs, starts them and reads the first
/// package: a stream that answers but sends no data is refused, naming it.
async fn rtde_stream(
    host: &str,
    hz: Option<f64>,
    reply: Duration,
) -> Result<(Rtde<TcpStream>, Measured), yarok_core::BoxError> {
    let stream = connect_within(host, RTDE_PORT, reply).await?;
    let mut settings = RtdeSettings::new(host);
    settings.reply_timeout = reply;
    let mut rtde = Rtde::connect(stream, settings).await?;
    let most = if rtde.controller_version().major >= 5 {
        500.0
    } else {
        125.0
    };
    rtde.setup_outputs(hz.unwrap_or(most).min(most), &OUTPUTS)
        .await?;
    rtde.start().await?;
    let first = rtde.receive().await.map_err(|error| match error {
        RtdeError::Timeout { seconds, .. } => format!(
            "RTDE answered, but sent no data package within {seconds} s of starting its stream: \
             the RTDE service is mute"
        )
        .into(),
        other => yarok_core::BoxError::from(other),
    })?;
    let first = measured(&first).ok_or("RTDE sent other values than asked for")?;
    Ok((rtde, first))
}

/// Connects to the secondary interface at `host`, which has sent its first robot state.
async fn secondary_stream(
    host: &str,
    reply: Duration,
) -> Result<Secondary<TcpStream>, yarok_core::BoxError> {
    let stream = connect_within(host, SECONDARY_PORT, reply).await?;
    Ok(Secondary::connect(stream, host, reply).await?)
}

/// What an RTDE package of [`OUTPUTS`] says.
fn measured(values: &[Value]) -> Option<Measured> {
    match *values {
        [
            Value::Vector6d(q),
            Value::Vector6d(qd),
            Value::Int32(robot_mode),
            Value::Int32(safety_mode),
        ] => Some(Measured {
            q,
            qd,
            robot_mode,
            safety_mode,
        }),
        _ => None,
    }
}

/// Connects to the arm's controller: the kinematics checked, the first joints read, and a task
/// that keeps the link fed; the arm is stopped at shutdown. Returns the link and the joints.
pub(super) async fn connect(
    bind: &mut Bind<Real>,
    kinematics: &Kinematics,
) -> Result<(Rc<RealLink>, Joints), BindError> {
    let CheckedSettings { settings, payload } = settings(bind)?;
    let host = settings.host.clone();
    let reply = Duration::try_from_secs_f64(settings.reply_seconds).unwrap_or_default();
    // Where connecting is, for a timeout to name.
    let step = Cell::new("");
    let connecting = async {
        step.set("opening its secondary interface (port 30002) and reading a robot state");
        let secondary = secondary_stream(&host, reply).await?;
        step.set("starting RTDE (port 30004) and reading the first joints");
        let rtde = rtde_stream(&host, settings.rtde_hz, reply).await?;
        step.set("asking its dashboard (port 29999) whether the robot is ready");
        check_ready(&host, reply).await?;
        Ok::<_, yarok_core::BoxError>((secondary, rtde))
    };
    let seconds = settings.connect_seconds;
    let (mut secondary, (rtde, first)) = tokio::time::timeout(
        Duration::try_from_secs_f64(seconds).unwrap_or_default(),
        connecting,
    )
    .await
    .map_err(|_| {
        bind.error(format!(
            "controller {host}: connecting did not finish within {seconds} s (the interface \
             setting connect_seconds); it was {}",
            step.get()
        ))
    })?
    .map_err(|e| {
        // The drivers' errors name the controller already; the checks' do not.
        let said = e.to_string();
        let named = format!("controller {host}");
        bind.error(if said.starts_with(&named) {
            said
        } else {
            format!("{named}: {said}")
        })
    })?;
    let reported = secondary
        .latest()
        .kinematics
        .ok_or_else(|| bind.error(format!("controller {host} sent no kinematics")))?;
    check_kinematics(bind, &kinematics.dh, &reported)?;
    let reverse = reverse_listener(&host, &settings)
        .await
        .map_err(|e| bind.error(e))?;
    if let Some(payload) = &payload {
        secondary
            .send_script(&script::set_payload(payload.mass, payload.centre))
            .await
            .map_err(|e| bind.error(e))?;
    }
    let link = Rc::new(RealLink {
        measured: Cell::new(first),
        received_at: Cell::new(Instant::now()),
        dropped_since_order: RefCell::new(None),
        requests: RefCell::new(VecDeque::new()),
        wake: Notify::new(),
        clock: bind.clock(),
        program_ended: RefCell::new(None),
    });
    bind.spawn(drive(Rc::clone(&link), settings, rtde, secondary, reverse));
    bind.on_stop(async move {
        // The driver's task has ended: a connection of its own stops the arm, without waiting
        // for a robot state (the interface may be what fell silent).
        let stopping = async {
            let mut stream = TcpStream::connect((host.as_str(), SECONDARY_PORT)).await?;
            send_script_and_close(&mut stream, &script::stopj(2.0), STOP_LINGER).await
        };
        tokio::time::timeout(reply, stopping).await.map_err(|_| {
            format!("controller {host}: no connection to send stopj within {reply:?}")
        })??;
        Ok(())
    });
    Ok((link, first.q))
}

/// The listener the streaming program connects back to, and the address it is told.
struct Reverse {
    listener: TcpListener,
    host: String,
    port: u16,
}

/// Listens for the streaming program of the controller at `controller`: on the interface
/// settings' `reverse_host` and `reverse_port`, by default on the address this computer
/// reaches the controller from.
async fn reverse_listener(
    controller: &str,
    settings: &Settings,
) -> Result<Reverse, yarok_core::BoxError> {
    let host = match &settings.reverse_host {
        Some(host) => host.clone(),
        None => {
            // A UDP socket "connected" to the controller holds the local address its route
            // leaves from; no packet is sent.
            let probe = std::net::UdpSocket::bind(("0.0.0.0", 0))?;
            probe.connect((controller, SECONDARY_PORT))?;
            probe.local_addr()?.ip().to_string()
        }
    };
    let port = settings.reverse_port;
    let listener = TcpListener::bind((host.as_str(), port))
        .await
        .map_err(|e| {
            format!(
                "cannot listen on {host}:{port} for the streaming program to connect back \
                 (the interface settings reverse_host and reverse_port): {e}"
            )
        })?;
    let port = listener.local_addr()?.port();
    Ok(Reverse {
        listener,
        host,
        port,
    })
}

/// The streaming program's connection, once it connected back by `until`.
async fn accept_program(
    reverse: &Reverse,
    until: Option<Instant>,
    reply: Duration,
) -> Result<TcpStream, String> {
    let Some(until) = until else {
        return std::future::pending().await;
    };
    let Reverse { host, port, .. } = reverse;
    match tokio::time::timeout_at(until, reverse.listener.accept()).await {
        Ok(Ok((stream, _))) => Ok(stream),
        Ok(Err(error)) => Err(format!(
            "its connection back to {host}:{port} failed: {error}"
        )),
        Err(_) => Err(format!(
            "it did not connect back to {host}:{port} within {} s: check that the controller \
             reaches this computer at {host} (the interface setting reverse_host) and that no \
             firewall blocks port {port}",
            reply.as_secs_f64()
        )),
    }
}

/// Resolves when the streaming program running, if one runs, closes its connection.
async fn program_closed(control: Option<&mut ExternalControl<TcpStream>>) {
    match control {
        Some(control) => {
            let _ = control.ended().await;
        }
        None => std::future::pending().await,
    }
}

/// Why a streaming program that closed its connection ended, as far as this side can tell.
fn closed_why(watchdog: Duration) -> String {
    format!(
        "it stopped the arm and closed its connection: it was stopped on the teach pendant or \
         replaced by another program, or its watchdog saw no target within {} s",
        watchdog.as_secs_f64()
    )
}

/// Keeps the link fed from RTDE (reconnecting a dropped stream within the reply time), sends
/// the scripts asked for, streams targets to the streaming program (sent when a stream
/// begins, and kept alive between targets), and serves dashboard requests.
async fn drive(
    link: Rc<RealLink>,
    settings: Settings,
    mut rtde: Rtde<TcpStream>,
    mut secondary: Secondary<TcpStream>,
    reverse: Reverse,
) -> Result<(), yarok_core::BoxError> {
    let reply = Duration::try_from_secs_f64(settings.reply_seconds).unwrap_or_default();
    let watchdog = Duration::try_from_secs_f64(settings.watchdog_seconds).unwrap_or_default();
    let host = settings.host.as_str();
    let secondary_again = async || secondary_stream(host, reply).await;
    // The streaming program: its connection once it connected back, or until when it may,
    // and the latest target that waits for it.
    let mut control: Option<ExternalControl<TcpStream>> = None;
    let mut connecting_until: Option<Instant> = None;
    let mut waiting: Option<(Joints, f64)> = None;
    let mut keep_alive = tokio::time::interval(watchdog / KEEP_ALIVES_PER_WATCHDOG);
    keep_alive.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    let end_program = |why: String| {
        *link.program_ended.borrow_mut() = Some((why, Instant::now()));
    };
    // The remote-control check runs beside the stream, never in its way: a dashboard that
    // answers late delays nothing that is sent.
    let mut remote_check: Pin<Box<dyn Future<Output = Result<(), yarok_core::BoxError>> + '_>> =
        Box::pin(std::future::pending());
    let mut checking = false;
    let mut sent_since_check = false;
    let mut next_check = tokio::time::interval(REMOTE_CHECK);
    next_check.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    loop {
        tokio::select! {
            _ = next_check.tick(), if !checking && sent_since_check => {
                remote_check = Box::pin(still_in_remote_control(host, reply));
                checking = true;
                sent_since_check = false;
            }
            checked = &mut remote_check, if checking => {
                checking = false;
                remote_check = Box::pin(std::future::pending());
                checked?;
            }
            values = rtde.receive() => match newest(&mut rtde, values).await {
                Ok(values) => {
                    if let Some(now) = measured(&values) {
                        report_a_halt(&link, &now, host, reply).await;
                        link.update(now);
                    }
                }
                Err(error) => {
                    tracing::warn!(controller = %host, "RTDE dropped ({error}); reconnecting");
                    link.dropped(format!("controller {host}'s RTDE stream: {error}"));
                    let first;
                    (rtde, first) = reconnect("RTDE", host, reply, error, async || {
                        rtde_stream(host, settings.rtde_hz, reply).await
                    })
                    .await?;
                    link.update(first);
                }
            },
            state = secondary.next_state() => {
                // Read to keep the controller's sending side flowing; RTDE is faster.
                if let Err(error) = state {
                    tracing::warn!(controller = %host, "secondary interface dropped ({error}); reconnecting");
                    link.dropped(format!("controller {host}'s secondary interface: {error}"));
                    secondary =
                        reconnect("secondary interface", host, reply, error, secondary_again).await?;
                }
            }
            accepted = accept_program(&reverse, connecting_until, reply) => {
                connecting_until = None;
                match accepted {
                    Ok(stream) => {
                        let mut program = ExternalControl::new(stream, watchdog, reply);
                        let first = match waiting.take() {
                            Some((target, seconds)) => program.servo(target, seconds).await,
                            None => program.keep_alive().await,
                        };
                        match first {
                            Ok(()) => control = Some(program),
                            Err(error) => end_program(error.to_string()),
                        }
                    }
                    Err(why) => end_program(why),
                }
            }
            () = program_closed(control.as_mut()) => {
                control = None;
                end_program(closed_why(watchdog));
            }
            _ = keep_alive.tick(), if control.is_some() => {
                if let Some(program) = control.as_mut()
                    && let Err(error) = program.keep_alive().await
                {
                    control = None;
                    end_program(error.to_string());
                }
            }
            () = link.wake.notified() => {
                let requests: Vec<Request> = link.requests.borrow_mut().drain(..).collect();
                for request in requests {
                    match request {
                        Request::Servo { target, seconds, max_speed } => {
                            sent_since_check = true;
                            if let Some(program) = control.as_mut() {
                                if let Err(error) = program.servo(target, seconds).await {
                                    control = None;
                                    end_program(error.to_string());
                                }
                                continue;
                            }
                            waiting = Some((target, seconds));
                            if connecting_until.is_some() || link.program_ended.borrow().is_some() {
                                continue;
                            }
                            let program = external_control::program(&ProgramSettings {
                                host: reverse.host.clone(),
                                port: reverse.port,
                                max_speed,
                                stop_deceleration: UR_JOINT_ACCELERATION,
                                lookahead: SERVO_LOOKAHEAD_S,
                                gain: SERVO_GAIN,
                            });
                            if let Err(error) = secondary.send_script(&program).await {
                                secondary =
                                    reconnect("secondary interface", host, reply, error, secondary_again)
                                        .await?;
                                secondary.send_script(&program).await?;
                            }
                            connecting_until = Some(Instant::now() + reply);
                        }
                        Request::Script(script) => {
                            sent_since_check = true;
                            // The script replaces the streaming program on the controller: it
                            // is told to stop first, and its end is no surprise.
                            if let Some(mut program) = control.take() {
                                let _ = program.stop().await;
                            }
                            connecting_until = None;
                            waiting = None;
                            if let Err(error) = secondary.send_script(&script).await {
                                secondary =
                                    reconnect("secondary interface", host, reply, error, secondary_again)
                                        .await?;
                                secondary.send_script(&script).await?;
                            }
                        }
                        Request::UnlockProtectiveStop(reply_to) => {
                            let unlocked = unlock(host, reply).await;
                            let _ = reply_to.send(unlocked);
                        }
                    }
                }
            }
        }
    }
}

/// The newest of the packages RTDE has sent: `received`'s, or the last of those already
/// waiting to be read after it. When the platform was not stepped for a while (a policy that
/// took long to think), the joints are then where the arm is now, not where it was then.
async fn newest(
    rtde: &mut Rtde<TcpStream>,
    received: Result<Vec<Value>, RtdeError>,
) -> Result<Vec<Value>, RtdeError> {
    let mut values = received?;
    loop {
        tokio::select! {
            biased;
            next = rtde.receive() => values = next?,
            () = std::future::ready(()) => return Ok(values),
        }
    }
}

/// How often, at most, the driver asks the dashboard whether the controller still takes
/// scripts (a controller switched to local control mid-run ignores them without a word): once
/// a period in which scripts were sent, beside the sending.
const REMOTE_CHECK: Duration = Duration::from_secs(1);

/// An error naming it when the controller at `host` has been switched to local control.
async fn still_in_remote_control(host: &str, reply: Duration) -> Result<(), yarok_core::BoxError> {
    if dashboard(host, reply).await?.is_in_remote_control().await? {
        return Ok(());
    }
    Err(format!(
        "controller {host} was switched to local control while running: it ignores the scripts \
         sent to it; switch it back to remote control on the teach pendant"
    )
    .into())
}

/// The `what` connection to `host` made again with `open` ([`reopen`] within `reply` of the
/// drop), or the error that dropped the old one and the last attempt's.
async fn reconnect<T>(
    what: &str,
    host: &str,
    reply: Duration,
    dropped: impl std::fmt::Display,
    open: impl AsyncFnMut() -> Result<T, yarok_core::BoxError>,
) -> Result<T, yarok_core::BoxError> {
    match reopen(reply, open).await {
        Ok(connection) => {
            tracing::info!(controller = %host, "{what} reconnected");
            Ok(connection)
        }
        Err(failed) => Err(format!(
            "{dropped}; {what} not back within {} s: {failed}",
            reply.as_secs_f64()
        )
        .into()),
    }
}

/// Refuses a controller that cannot move the arm, saying why in words: in local control, the
/// arm powered off or its brakes locked, or its safety system holding it.
async fn check_ready(host: &str, reply: Duration) -> Result<(), yarok_core::BoxError> {
    let mut dashboard = dashboard(host, reply).await?;
    if !dashboard.is_in_remote_control().await? {
        return Err(
            "the controller is in local control and runs no script sent to it: switch it \
                    to remote control on the teach pendant"
                .into(),
        );
    }
    match dashboard.robot_mode().await? {
        RobotMode::Running => {}
        RobotMode::PowerOff => {
            return Err(
                "the arm is powered off: power it on and release its brakes (on the \
                        teach pendant, or the dashboard's `power on` and `brake release`)"
                    .into(),
            );
        }
        RobotMode::PowerOn | RobotMode::Idle => {
            return Err(
                "the arm's brakes are locked: release them (on the teach pendant, or \
                        the dashboard's `brake release`)"
                    .into(),
            );
        }
        other => return Err(format!("the arm is not running: its mode is {other:?}").into()),
    }
    let holding = match dashboard.safety_status().await? {
        SafetyStatus::Normal | SafetyStatus::Reduced => return Ok(()),
        SafetyStatus::ProtectiveStop => "PROTECTIVE_STOP".to_owned(),
        SafetyStatus::Other(status) => status,
        other => format!("{other:?}"),
    };
    Err(format!(
        "the arm's safety system holds it ({holding}): inspect the cause, then clear it (unlock \
         a protective stop, release an emergency stop)"
    )
    .into())
}

/// Warns, in the dashboard's words, when RTDE says the arm has just stopped being able to move
/// (RTDE's packages wait in the socket meanwhile).
async fn report_a_halt(link: &RealLink, now: &Measured, host: &str, reply: Duration) {
    let halted = |m: &Measured| m.robot_mode != 7 || m.safety_mode > 2;
    if halted(now) && !halted(&link.measured.get()) {
        match check_ready(host, reply).await {
            Ok(()) => {}
            Err(state) => tracing::warn!(controller = %host, "the arm stopped: {state}"),
        }
    }
}

/// `unlock protective stop` on the dashboard of `host`.
async fn unlock(host: &str, reply: Duration) -> Result<(), String> {
    let unlocking = async {
        dashboard(host, reply)
            .await?
            .unlock_protective_stop()
            .await?;
        Ok::<_, yarok_core::BoxError>(())
    };
    match tokio::time::timeout(reply * 2, unlocking).await {
        Ok(result) => result.map_err(|e| e.to_string()),
        Err(_) => Err(format!(
            "dashboard {host}: no answer within {} s",
            reply.as_secs_f64() * 2.0
        )),
    }
}
