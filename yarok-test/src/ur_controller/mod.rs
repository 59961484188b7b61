//! A fake UR controller for tests, on a loopback address of its own, in a CB3 (3.15) or an
//! e-Series (5.11) profile: its RTDE server (port 30004) answers recipes from the controller's
//! variable table and streams data packages at the recipe's rate; its dashboard server (port
//! 29999) powers the arm, releases its brakes, unlocks protective stops (not within 5 s of
//! one) and loads and plays programs, with UR's replies; its secondary interface (port 30002)
//! sends a version message and robot states at 10 Hz in the profile's layout (a UR5's
//! kinematics on CB3, a UR5e's on e-Series) and runs `movej`/`movel`/`stopj`/`stopl` lines;
//! its real-time interface (port 30003) streams the 1116-byte packet at 125 or 500 Hz and runs
//! script lines too; its Robotiq gripper socket (port 63352) activates a 2F-85 whose fingers
//! move in time at the speed asked for and stop on an object the test places, or fault when
//! told to. Faults a test can cause: every connection dropped at once, a mute RTDE or secondary
//! interface (connections open, nothing sent), local control, power off, a protective stop.
//! The arm moves as its [`ArmMotion`] does: the project's simulated UR model in the
//! workspace's tests, a linear stand-in in yarok-hw's protocol tests. Shared by yarok-hw's
//! tests and the workspace's.

use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::net::TcpListener;
use yarok_hw::ur::rtde::{ControllerVersion, Value};

mod dashboard;
mod external_control;
mod gripper;
pub mod motion;
mod realtime;
mod rtde;
mod secondary;

use motion::{ArmCommand, ArmMotion, Interpolated};

pub use external_control::ProgramEvent;

use dashboard::serve_dashboard;
use gripper::{Fingers, serve_gripper};
use realtime::serve_realtime;
use rtde::serve_rtde;
use secondary::serve_secondary;

/// RTDE's and the dashboard's ports, which third-party clients do not let one change.
pub const RTDE_PORT: u16 = 30004;
/// The dashboard server's port.
pub const DASHBOARD_PORT: u16 = 29999;
/// The Robotiq URCap's gripper socket.
pub const GRIPPER_PORT: u16 = 63352;
/// The secondary interface.
pub const SECONDARY_PORT: u16 = 30002;
/// The real-time interface.
pub const REALTIME_PORT: u16 = 30003;

/// Which controller it plays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Profile {
    /// A CB3 controller, software 3.15: RTDE up to 125 Hz.
    Cb3,
    /// An e-Series controller, software 5.11: RTDE up to 500 Hz.
    ESeries,
}

impl Profile {
    /// The controller software's version it reports.
    pub fn version(self) -> ControllerVersion {
        match self {
            Profile::Cb3 => ControllerVersion {
                major: 3,
                minor: 15,
                bugfix: 7,
                build: 106_331,
            },
            Profile::ESeries => ControllerVersion {
                major: 5,
                minor: 11,
                bugfix: 1,
                build: 108_318,
            },
        }
    }

    /// The dashboard's `PolyscopeVersion` reply.
    fn polyscope(self) -> String {
        let ControllerVersion {
            major,
            minor,
            bugfix,
            build,
        } = self.version();
        format!("URSoftware {major}.{minor}.{bugfix}.{build} (Mar 22 2022)")
    }

    fn max_frequency(self) -> f64 {
        match self {
            Profile::Cb3 => 125.0,
            Profile::ESeries => 500.0,
        }
    }
}

/// What the controller's clients see and set.
struct Shared {
    profile: Profile,
    started: Instant,
    motion: Mutex<Box<dyn ArmMotion>>,
    /// Input variables clients have written.
    inputs: Mutex<HashMap<String, Value>>,
    /// Output variables clients asked for, in order.
    asked: Mutex<Vec<String>>,
    arm: Mutex<Arm>,
    fingers: Mutex<Fingers>,
    /// URScript lines clients sent (a program whole), each with when it arrived.
    scripts: Mutex<Vec<(Instant, String)>>,
    /// The streaming programs' runs: each message, each controller step, each end.
    program_events: Mutex<Vec<(Instant, ProgramEvent)>>,
    /// Set to end the streaming program running, if one runs.
    running_program: Mutex<Option<Arc<std::sync::atomic::AtomicBool>>>,
    /// How late the dashboard answers each command.
    dashboard_delay: Mutex<Duration>,
    /// The TCP the last `set_tcp` set.
    tcp: Mutex<[f64; 6]>,
    /// Bumped to drop every RTDE, secondary and gripper connection.
    drops: AtomicU32,
    /// RTDE connections accepted so far.
    rtde_connections: AtomicU32,
    /// Set while RTDE sends no data package (its connections stay open and answer requests).
    rtde_mute: std::sync::atomic::AtomicBool,
    /// Set while the secondary interface sends no robot state (its connections stay open).
    secondary_mute: std::sync::atomic::AtomicBool,
    /// Set while the gripper socket answers nothing (its connections stay open).
    gripper_mute: std::sync::atomic::AtomicBool,
    /// Set when the fake is dropped: its sessions end.
    closed: std::sync::atomic::AtomicBool,
}

impl Shared {
    /// The arm's mode as the secondary interface and RTDE number it.
    fn robot_mode(&self) -> u8 {
        match self.arm.lock().unwrap().robot_mode {
            "POWER_OFF" => 3,
            "IDLE" => 5,
            _ => 7,
        }
    }
}

/// The arm's power, safety and program, as the dashboard reports and changes them.
#[derive(Debug, Clone)]
pub struct Arm {
    /// The dashboard's `robotmode` (`POWER_OFF`, `IDLE`, `RUNNING`).
    pub robot_mode: &'static str,
    /// The dashboard's `safetystatus` (`NORMAL`, `PROTECTIVE_STOP`).
    pub safety: &'static str,
    /// When the protective stop happened.
    pub stopped_at: Option<Instant>,
    /// The program loaded, if any.
    pub program: Option<String>,
    /// Whether the program is playing.
    pub playing: bool,
    /// False in local control (e-Series): scripts from the network are not run.
    pub remote_control: bool,
}

/// A fake controller serving RTDE on `host`, on a thread of its own until dropped.
pub struct FakeController {
    /// Its loopback address, unique to it.
    pub host: String,
    shared: Arc<Shared>,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl std::fmt::Debug for FakeController {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FakeController")
            .field("host", &self.host)
            .finish_non_exhaustive()
    }
}

/// A loopback address no other fake of this process or another test process uses.
fn unique_loopback() -> String {
    static NEXT: AtomicU32 = AtomicU32::new(1);
    let pid = std::process::id();
    let own = NEXT.fetch_add(1, Ordering::Relaxed) % 254 + 1;
    format!("127.{}.{}.{own}", (pid >> 8) & 0xFF, pid & 0xFF)
}

impl FakeController {
    /// One whose arm is the [`Interpolated`] stand-in, upright.
    pub fn start(profile: Profile) -> Self {
        Self::with_arm(
            profile,
            Box::new(Interpolated::at([
                0.0, -FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2, 0.0,
            ])),
        )
    }

    /// One whose arm moves as `motion` does.
    pub fn with_arm(profile: Profile, motion: Box<dyn ArmMotion>) -> Self {
        let host = unique_loopback();
        let shared = Arc::new(Shared {
            profile,
            started: Instant::now(),
            motion: Mutex::new(motion),
            scripts: Mutex::new(Vec::new()),
            program_events: Mutex::new(Vec::new()),
            running_program: Mutex::new(None),
            dashboard_delay: Mutex::new(Duration::ZERO),
            tcp: Mutex::new([0.0; 6]),
            inputs: Mutex::new(HashMap::new()),
            asked: Mutex::new(Vec::new()),
            drops: AtomicU32::new(0),
            rtde_connections: AtomicU32::new(0),
            rtde_mute: std::sync::atomic::AtomicBool::new(false),
            secondary_mute: std::sync::atomic::AtomicBool::new(false),
            gripper_mute: std::sync::atomic::AtomicBool::new(false),
            closed: std::sync::atomic::AtomicBool::new(false),
            arm: Mutex::new(Arm {
                robot_mode: "RUNNING",
                safety: "NORMAL",
                stopped_at: None,
                program: None,
                playing: false,
                remote_control: true,
            }),
            fingers: Mutex::new(Fingers::new()),
        });
        let address = |port: u16| -> SocketAddr { format!("{host}:{port}").parse().unwrap() };
        let (rtde, dashboard, gripper, secondary, realtime) = (
            address(RTDE_PORT),
            address(DASHBOARD_PORT),
            address(GRIPPER_PORT),
            address(SECONDARY_PORT),
            address(REALTIME_PORT),
        );
        let (bound_tx, bound_rx) = std::sync::mpsc::channel();
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let serving = Arc::clone(&shared);
        let thread = std::thread::spawn(move || {
            let runtime = tokio::runtime::Builder::new_current_thread()
                .enable_all()
                .build()
                .unwrap();
            runtime.block_on(async move {
                let rtde = TcpListener::bind(rtde).await.expect("the RTDE port binds");
                let dashboard = TcpListener::bind(dashboard)
                    .await
                    .expect("the dashboard port binds");
                let gripper = TcpListener::bind(gripper)
                    .await
                    .expect("the gripper port binds");
                let secondary = TcpListener::bind(secondary)
                    .await
                    .expect("the secondary port binds");
                let realtime = TcpListener::bind(realtime)
                    .await
                    .expect("the real-time port binds");
                bound_tx.send(()).unwrap();
                let accepting = async {
                    loop {
                        tokio::select! {
                            Ok((stream, _)) = rtde.accept() => {
                                serving.rtde_connections.fetch_add(1, Ordering::Relaxed);
                                let serving = Arc::clone(&serving);
                                if let Ok(stream) = stream.into_std() {
                                    let _ = stream.set_nonblocking(false);
                                    std::thread::spawn(move || serve_rtde(stream, serving));
                                }
                            }
                            Ok((stream, _)) = dashboard.accept() => {
                                tokio::spawn(serve_dashboard(stream, Arc::clone(&serving)));
                            }
                            Ok((stream, _)) = gripper.accept() => {
                                tokio::spawn(serve_gripper(stream, Arc::clone(&serving)));
                            }
                            Ok((stream, _)) = secondary.accept() => {
                                tokio::spawn(serve_secondary(stream, Arc::clone(&serving)));
                            }
                            Ok((stream, _)) = realtime.accept() => {
                                tokio::spawn(serve_realtime(stream, Arc::clone(&serving)));
                            }
                        }
                    }
                };
                tokio::select! {
                    () = accepting => {}
                    _ = stopped => {}
                }
            });
        });
        bound_rx.recv().expect("the fake controller starts");
        Self {
            host,
            shared,
            stop: Some(stop),
            thread: Some(thread),
        }
    }

    /// Puts the arm at rest at `q` (radians).
    pub fn set_joints(&self, q: [f64; 6]) {
        self.shared.motion.lock().unwrap().place(q);
    }

    /// Where the arm is now (moving, if a script moves it).
    pub fn joints(&self) -> [f64; 6] {
        self.shared.motion.lock().unwrap().state().q
    }

    /// The URScript clients sent, a line each.
    pub fn scripts(&self) -> Vec<String> {
        let scripts = self.shared.scripts.lock().unwrap();
        scripts.iter().map(|(_, line)| line.clone()).collect()
    }

    /// The URScript clients sent, a line each, with when it arrived.
    pub fn scripts_arrived(&self) -> Vec<(Instant, String)> {
        self.shared.scripts.lock().unwrap().clone()
    }

    /// What the streaming programs did, each with when: started, each message read, each
    /// controller step's joints, and why each ended.
    pub fn program_events(&self) -> Vec<(Instant, ProgramEvent)> {
        self.shared.program_events.lock().unwrap().clone()
    }

    /// The joints each controller step of the streaming programs commanded, with when.
    pub fn program_steps(&self) -> Vec<(Instant, [f64; 6])> {
        let events = self.shared.program_events.lock().unwrap();
        let steps = events.iter().filter_map(|(at, event)| match event {
            ProgramEvent::Step(q) => Some((*at, *q)),
            _ => None,
        });
        steps.collect()
    }

    /// The targets the streaming programs read (keep-alives and stops left out), with when.
    pub fn program_targets(&self) -> Vec<(Instant, [f64; 6], f64)> {
        let events = self.shared.program_events.lock().unwrap();
        let targets = events.iter().filter_map(|(at, event)| match event {
            ProgramEvent::Message(message)
                if message.mode == yarok_hw::ur::external_control::Mode::Servo =>
            {
                Some((*at, message.q, message.period))
            }
            _ => None,
        });
        targets.collect()
    }

    /// How many streaming programs connected back to their sender.
    pub fn programs_started(&self) -> usize {
        let events = self.shared.program_events.lock().unwrap();
        let started = events
            .iter()
            .filter(|(_, event)| *event == ProgramEvent::Started);
        started.count()
    }

    /// Why each streaming program ended, with when.
    pub fn program_ends(&self) -> Vec<(Instant, String)> {
        let events = self.shared.program_events.lock().unwrap();
        let ends = events.iter().filter_map(|(at, event)| match event {
            ProgramEvent::Ended(why) => Some((*at, why.clone())),
            _ => None,
        });
        ends.collect()
    }

    /// Makes the dashboard answer each command `delay` late, as a busy controller does.
    pub fn set_dashboard_delay(&self, delay: Duration) {
        *self.shared.dashboard_delay.lock().unwrap() = delay;
    }

    /// Turns the arm off, as `power off` on the dashboard does.
    pub fn power_off(&self) {
        self.shared.arm.lock().unwrap().robot_mode = "POWER_OFF";
    }

    /// The value a client last wrote to the input variable `name`.
    pub fn input(&self, name: &str) -> Option<Value> {
        self.shared.inputs.lock().unwrap().get(name).copied()
    }

    /// The arm's power, safety and program now.
    pub fn arm(&self) -> Arm {
        self.shared.arm.lock().unwrap().clone()
    }

    /// A protective stop, `ago` in the past.
    pub fn protective_stop(&self, ago: Duration) {
        self.shared.motion.lock().unwrap().command(ArmCommand::Stop);
        let mut arm = self.shared.arm.lock().unwrap();
        arm.safety = "PROTECTIVE_STOP";
        arm.stopped_at = Some(Instant::now() - ago);
        arm.playing = false;
    }

    /// The emergency stop button pressed on the robot: the arm stops where it is.
    pub fn emergency_stop(&self) {
        self.shared.motion.lock().unwrap().command(ArmCommand::Stop);
        let mut arm = self.shared.arm.lock().unwrap();
        arm.safety = "ROBOT_EMERGENCY_STOP";
        arm.playing = false;
    }

    /// The gripper now.
    pub fn fingers(&self) -> Fingers {
        let mut fingers = self.shared.fingers.lock().unwrap();
        fingers.update(Instant::now());
        fingers.clone()
    }

    /// Puts an object between the fingers: closing, they stop at `position`.
    pub fn place_object(&self, position: Option<u8>) {
        self.shared.fingers.lock().unwrap().object_at = position;
    }

    /// Makes the gripper report fault `code` (its fingers stop).
    pub fn gripper_fault(&self, code: u8) {
        self.shared.fingers.lock().unwrap().flt = code;
    }

    /// Stops the secondary interface's robot states, its connections left open (a controller
    /// whose secondary interface hangs while RTDE streams).
    pub fn mute_secondary(&self) {
        self.shared.secondary_mute.store(true, Ordering::Relaxed);
    }

    /// Makes the gripper socket answer nothing, its connections (and new ones) left open (a
    /// gripper whose URCap hangs, a cable pulled between the wrist and the gripper).
    pub fn mute_gripper(&self) {
        self.shared.gripper_mute.store(true, Ordering::Relaxed);
    }

    /// Stops RTDE's data packages, its connections (and new ones) left open and answering
    /// requests (a controller whose RTDE service hangs); `false` lets them flow again.
    pub fn mute_rtde(&self, mute: bool) {
        self.shared.rtde_mute.store(mute, Ordering::Relaxed);
    }

    /// How many RTDE connections were accepted so far.
    pub fn rtde_connections(&self) -> u32 {
        self.shared.rtde_connections.load(Ordering::Relaxed)
    }

    /// Puts the controller in local (`false`) or remote (`true`) control, as its teach
    /// pendant does: in local control it runs no script from the network.
    pub fn set_remote_control(&self, remote: bool) {
        self.shared.arm.lock().unwrap().remote_control = remote;
    }

    /// Drops every RTDE, secondary and gripper connection, as a network hiccup does.
    pub fn drop_streams(&self) {
        self.shared.drops.fetch_add(1, Ordering::Relaxed);
    }

    /// Restarts the controller as its power cycle does: the program running stops (the arm
    /// halts where it is) and every connection drops.
    pub fn restart(&self) {
        self.shared.end_program();
        self.shared.motion.lock().unwrap().command(ArmCommand::Stop);
        self.shared.arm.lock().unwrap().playing = false;
        self.drop_streams();
    }

    /// The output variables clients asked for so far.
    pub fn asked(&self) -> Vec<String> {
        self.shared.asked.lock().unwrap().clone()
    }
}

impl Drop for FakeController {
    fn drop(&mut self) {
        self.shared.closed.store(true, Ordering::Relaxed);
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
