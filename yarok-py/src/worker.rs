//! [`Worker`]: a world on a thread of its own — the platform is built, stepped and shut down
//! there (it is not `Send`) — driven by requests over a channel, so that Python waits for it
//! without the GIL and N worlds step on N threads.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, TryRecvError, channel};
use std::thread::JoinHandle;
use std::time::Duration;

use yarok::components::demos::{self, Demo};
use yarok::components::features::{Features, Observation, check_action_length};
use yarok::core::component::ComponentType;
use yarok::core::runtime::Platform;
use yarok::core::suggest::did_you_mean;
use yarok::mjc::{SimBackend, Warnings};

use crate::exports::exported;

/// How a world is made: a bundled world's tag, the environment, and the command line's
/// settings (`--set`, `--config`).
#[derive(Debug, Clone)]
pub(crate) struct WorldSpec {
    pub(crate) world: String,
    pub(crate) environment: String,
    pub(crate) settings: Vec<String>,
    pub(crate) configs: Vec<String>,
    /// Cameras of the model observed as images (`overview`), and their size.
    pub(crate) cameras: Vec<String>,
    pub(crate) camera_size: [u32; 2],
}

/// A free body put somewhere when an episode begins.
#[derive(Debug, Clone)]
pub(crate) struct BodyPlacement {
    pub(crate) body: String,
    pub(crate) position: [f64; 3],
    pub(crate) orientation: [f64; 4],
}

/// What a world's observations and actions are, found when it starts.
#[derive(Debug, Clone)]
pub(crate) struct WorldInfo {
    pub(crate) state_names: Vec<String>,
    pub(crate) environment_names: Vec<String>,
    pub(crate) images: Vec<(String, [u32; 2])>,
    pub(crate) action_names: Vec<String>,
    pub(crate) action_ranges: Vec<[f64; 2]>,
    pub(crate) timestep: f64,
}

impl WorldInfo {
    /// Whether the world takes `action` as far as its names and ranges go: checked for every
    /// world of a vector before any is sent its action, so that one refusal leaves all as
    /// they were.
    pub(crate) fn check_action(&self, action: &[f64]) -> Result<(), String> {
        check_action_length(&self.action_names, action)?;
        let named = self.action_names.iter().zip(&self.action_ranges);
        for ((name, [lowest, highest]), value) in named.zip(action) {
            if !(lowest..=highest).contains(&value) {
                return Err(format!(
                    "the target of {name} is {value}, outside its range {lowest} to {highest}"
                ));
            }
        }
        Ok(())
    }
}

/// An observation with the platform time and tick it was taken at.
#[derive(Debug)]
pub(crate) struct Observed {
    pub(crate) observation: Observation,
    pub(crate) time: f64,
    pub(crate) ticks: u64,
    /// What MuJoCo warned of in the steps since the last observation, in words.
    pub(crate) warnings: Vec<&'static str>,
}

enum Request {
    /// Begin episode `episode`: the world back at its start, then the bodies placed, then one
    /// tick so that every sensor sees the start.
    Reset {
        episode: u64,
        placements: Vec<BodyPlacement>,
    },
    /// Set the action (if any), then `periods` times: advance `ticks` ticks and observe.
    Step {
        action: Option<Vec<f64>>,
        ticks: u64,
        periods: u64,
    },
    /// Stop the platform: devices left safe, plugins ended.
    Close,
}

type Reply = Result<Observed, String>;

/// A world on its own thread.
#[derive(Debug)]
pub(crate) struct Worker {
    requests: Sender<Request>,
    replies: Receiver<Reply>,
    /// How the run ended, sent once the platform has shut down.
    ended: Receiver<Result<(), String>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
    info: WorldInfo,
    closed: bool,
}

/// Whether this process has started a world (its thread, and EGL's).
static WORLDS_STARTED: AtomicBool = AtomicBool::new(false);

/// Whether this process is a fork of one that had started worlds: their threads are not here,
/// and the locks they held (EGL's, Mesa's) stay held for good.
static FORKED_AFTER_WORLDS: AtomicBool = AtomicBool::new(false);

/// Notes that this process was just forked (called in the child, by `os.register_at_fork`).
pub(crate) fn forked() {
    if WORLDS_STARTED.load(Ordering::Relaxed) {
        FORKED_AFTER_WORLDS.store(true, Ordering::Relaxed);
    }
}

/// Notes that a world is starting in this process; refused in a fork of a process that had
/// started worlds.
pub(crate) fn starting() -> Result<(), String> {
    if FORKED_AFTER_WORLDS.load(Ordering::Relaxed) {
        return Err(
            "this process was forked from one that had started yarok worlds, whose threads and \
             rendering locks a fork does not carry: start processes with multiprocessing's \
             \"spawn\" method (gymnasium.make_vec(…, vectorization_mode=\"async\", \
             vector_kwargs={\"context\": \"spawn\"}))"
                .into(),
        );
    }
    WORLDS_STARTED.store(true, Ordering::Relaxed);
    Ok(())
}

/// How long a wait for the world's thread lasts before the caller looks for Ctrl-C.
pub(crate) const POLL: Duration = Duration::from_millis(50);

impl Worker {
    /// Starts the world of `spec` on a new thread and waits until its components are bound,
    /// calling `interrupted` every [`POLL`] (Python's Ctrl-C).
    pub(crate) fn start(
        spec: WorldSpec,
        interrupted: &mut dyn FnMut() -> bool,
    ) -> Result<Self, String> {
        starting()?;
        let (requests, inbox) = channel();
        let (outbox, replies) = channel();
        let (started, start_reply) = channel();
        let (end, ended) = channel();
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::Builder::new()
            .name(format!("yarok {}", spec.world))
            .spawn(move || serve(spec, flag, inbox, outbox, started, end))
            .map_err(|e| format!("cannot start the world's thread: {e}"))?;
        let info = loop {
            match start_reply.recv_timeout(POLL) {
                Ok(result) => break result?,
                Err(RecvTimeoutError::Timeout) if interrupted() => {
                    stop.store(true, Ordering::Relaxed);
                    let _ = thread.join();
                    return Err("interrupted while the world started".into());
                }
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => {
                    return Err("the world's thread ended while starting".into());
                }
            }
        };
        Ok(Self {
            requests,
            replies,
            ended,
            stop,
            thread: Some(thread),
            info,
            closed: false,
        })
    }

    pub(crate) fn info(&self) -> &WorldInfo {
        &self.info
    }

    /// Sends a reset; its reply is taken with [`Worker::reply`].
    pub(crate) fn send_reset(
        &self,
        episode: u64,
        placements: Vec<BodyPlacement>,
    ) -> Result<(), String> {
        self.send(Request::Reset {
            episode,
            placements,
        })
    }

    /// Sends a step of `ticks` ticks, observed after them; its reply is taken with
    /// [`Worker::reply`].
    pub(crate) fn send_step(&self, action: Option<Vec<f64>>, ticks: u64) -> Result<(), String> {
        self.send_steps(action, ticks, 1)
    }

    /// Sends `periods` steps of `ticks` ticks each, each observed as a step is, the action
    /// set before the first; the reply (the last observation) is taken with [`Worker::reply`].
    pub(crate) fn send_steps(
        &self,
        action: Option<Vec<f64>>,
        ticks: u64,
        periods: u64,
    ) -> Result<(), String> {
        self.send(Request::Step {
            action,
            ticks,
            periods,
        })
    }

    fn send(&self, request: Request) -> Result<(), String> {
        if self.closed {
            return Err("the world is closed".into());
        }
        self.requests
            .send(request)
            .map_err(|_| "the world's thread has ended".to_owned())
    }

    /// The reply to the request sent last, waiting [`POLL`] at a time; `None` when
    /// `interrupted` says to stop waiting (the world is then stopped).
    pub(crate) fn reply(&mut self, interrupted: &mut dyn FnMut() -> bool) -> Option<Reply> {
        loop {
            match self.replies.recv_timeout(POLL) {
                Ok(reply) => return Some(reply),
                Err(RecvTimeoutError::Timeout) if interrupted() => {
                    self.stop.store(true, Ordering::Relaxed);
                    let _ = self.finish();
                    return None;
                }
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => {
                    return Some(Err("the world's thread ended".into()));
                }
            }
        }
    }

    /// Asks the world to stop at its next tick, without waiting: a long step under way ends
    /// there (devices left safe as the platform stops). [`Worker::close`] then waits for it.
    pub(crate) fn interrupt(&self) {
        self.stop.store(true, Ordering::Relaxed);
    }

    /// Stops the world — devices left safe — and waits for its thread: how the run ended.
    pub(crate) fn close(&mut self) -> Result<(), String> {
        if self.closed {
            return Ok(());
        }
        let _ = self.requests.send(Request::Close);
        self.finish()
    }

    fn finish(&mut self) -> Result<(), String> {
        self.closed = true;
        let Some(thread) = self.thread.take() else {
            return Ok(());
        };
        let outcome = self
            .ended
            .recv()
            .unwrap_or_else(|_| Err("the world's thread ended without a word".into()));
        thread
            .join()
            .map_err(|_| "the world's thread panicked".to_owned())?;
        outcome
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        let _ = self.close();
    }
}

/// The bundled world tagged `world` with its demo behaviours (what `run` runs), or an error
/// naming the bundled worlds.
pub(crate) fn bundled(world: &str) -> Result<Demo, String> {
    demos::find(world).ok_or_else(|| {
        let tags: Vec<String> = demos::demos().iter().map(Demo::tag).collect();
        refusal(format!("no bundled world {world:?}"), world, &tags, "")
    })
}

/// The world tagged `world` that `World` opens: this module's own, then the bundled ones; or
/// an error naming them all.
fn world_tagged(world: &str) -> Result<ComponentType, String> {
    exported()
        .world_tagged(world)
        .or_else(|| demos::find(world).map(|demo| demo.world))
        .ok_or_else(|| {
            let tags: Vec<String> = exported()
                .world_tags()
                .into_iter()
                .chain(demos::demos().iter().map(Demo::tag))
                .collect();
            refusal(
                format!("no world {world:?}"),
                world,
                &tags,
                "; or a template file's path",
            )
        })
}

/// `refused` (`no world "x"`), the tag of `tags` nearest `world` suggested, then all of them
/// and `more`.
fn refusal(refused: String, world: &str, tags: &[String], more: &str) -> String {
    format!(
        "{refused}{} (the worlds: {}{more})",
        did_you_mean(world, tags.iter().map(String::as_str)),
        tags.join(", ")
    )
}

/// The platform of `spec`, built and started (its components bound).
fn start(spec: &WorldSpec, stop: Arc<AtomicBool>) -> Result<(Platform, Features), String> {
    let builder = if std::path::Path::new(&spec.world).is_file() {
        yarok::platform().world_declaration(exported().template_world(&spec.world))
    } else if spec.world.ends_with(".xml") {
        return Err(format!("no template file {:?}", spec.world));
    } else {
        yarok::platform().world_type(world_tagged(&spec.world)?)
    };
    let args = ["--env".to_owned(), spec.environment.clone()]
        .into_iter()
        .chain(
            spec.settings
                .iter()
                .flat_map(|s| ["--set".to_owned(), s.clone()]),
        )
        .chain(
            spec.configs
                .iter()
                .flat_map(|c| ["--config".to_owned(), c.clone()]),
        );
    let mut platform = builder
        .args(args)
        .map_err(|e| e.to_string())?
        .stop_flag(stop)
        .ctrl_c(false)
        .behaviour_named("python", |pl| async move {
            pl.wait_forever().await?;
            Ok(())
        })
        .build()
        .map_err(|e| e.to_string())?;
    if !platform.step().map_err(|e| e.to_string())? {
        return Err("the world stopped as it started".into());
    }
    let features = Features::of(&platform.world(), &spec.cameras, spec.camera_size, false)
        .map_err(|e| e.to_string())?;
    Ok((platform, features))
}

fn info(platform: &Platform, features: &Features) -> WorldInfo {
    WorldInfo {
        state_names: features.state_names().to_vec(),
        environment_names: features.environment_names().to_vec(),
        images: features
            .images()
            .iter()
            .map(|image| (image.key.clone(), image.size))
            .collect(),
        action_names: features.action_names().to_vec(),
        action_ranges: features.action_ranges().to_vec(),
        timestep: platform.pl().timestep(),
    }
}

/// The world's thread: starts it, then answers requests until closed.
fn serve(
    spec: WorldSpec,
    stop: Arc<AtomicBool>,
    inbox: Receiver<Request>,
    outbox: Sender<Reply>,
    started: Sender<Result<WorldInfo, String>>,
    end: Sender<Result<(), String>>,
) {
    let (mut platform, mut features) = match start(&spec, stop) {
        Ok(started) => started,
        Err(error) => {
            let _ = started.send(Err(error));
            return;
        }
    };
    if started.send(Ok(info(&platform, &features))).is_err() {
        return;
    }
    // Hardware does not wait for Python: between requests a real world goes on ticking (its
    // drivers reading the devices, the arm holding or approaching its last target), so that a
    // policy that thinks long finds fresh observations and no stalled connection.
    let free_running = spec.environment == "real";
    // The tick the last reply was taken at: a free-running world's step ends a whole number of
    // ticks after it (the ticks run meanwhile count), keeping the control rate.
    let mut last_reply = platform.pl().ticks();
    loop {
        let request = if free_running {
            match inbox.try_recv() {
                Ok(request) => request,
                Err(TryRecvError::Empty) => match platform.step() {
                    Ok(true) => continue,
                    Ok(false) => break,
                    Err(error) => {
                        let _ = outbox.send(Err(error.to_string()));
                        break;
                    }
                },
                Err(TryRecvError::Disconnected) => break,
            }
        } else {
            match inbox.recv() {
                Ok(request) => request,
                Err(_) => break,
            }
        };
        // A refused action or placement leaves the world as it was; a failed tick ends it.
        let (reply, ended) = match request {
            Request::Reset {
                episode,
                placements,
            } => match begin(&platform, &features, episode, &placements) {
                Ok(()) => advance(&mut platform, &mut features, 1),
                Err(refused) => (Err(refused), false),
            },
            Request::Step {
                action,
                ticks,
                periods,
            } => match act(&platform, &features, action) {
                Ok(()) if free_running => {
                    let mut reply = (Err("no period".into()), false);
                    for period in 1..=periods {
                        let due = last_reply + period * ticks;
                        let left = due.saturating_sub(platform.pl().ticks()).max(1);
                        reply = advance(&mut platform, &mut features, left);
                        if reply.1 {
                            break;
                        }
                    }
                    reply
                }
                Ok(()) => {
                    let mut reply = advance(&mut platform, &mut features, ticks);
                    for _ in 1..periods {
                        if reply.1 {
                            break;
                        }
                        reply = advance(&mut platform, &mut features, ticks);
                    }
                    reply
                }
                Err(refused) => (Err(refused), false),
            },
            Request::Close => break,
        };
        last_reply = platform.pl().ticks();
        if outbox.send(reply).is_err() || ended {
            break;
        }
    }
    platform.pl().stop();
    let outcome = platform.step().map(drop).map_err(|e| e.to_string());
    let _ = end.send(outcome);
}

/// Begins episode `episode`: the world back at its start, the bodies placed.
fn begin(
    platform: &Platform,
    features: &Features,
    episode: u64,
    placements: &[BodyPlacement],
) -> Result<(), String> {
    platform
        .pl()
        .begin_episode(episode)
        .map_err(|e| e.to_string())?;
    for placement in placements {
        features
            .place(
                &platform.world(),
                &placement.body,
                placement.position,
                placement.orientation,
            )
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn act(platform: &Platform, features: &Features, action: Option<Vec<f64>>) -> Result<(), String> {
    match action {
        Some(action) => features
            .act(&platform.world(), &action)
            .map_err(|e| e.to_string()),
        None => Ok(()),
    }
}

/// MuJoCo's warning counts now, in `sim`.
fn warnings(platform: &Platform) -> Option<Warnings> {
    let world = platform.world();
    let sim = world.backend::<SimBackend>()?;
    Some(sim.data().warnings())
}

/// Advances `ticks` ticks, then observes; whether the world ended.
fn advance(platform: &mut Platform, features: &mut Features, ticks: u64) -> (Reply, bool) {
    let before = warnings(platform);
    for _ in 0..ticks {
        match platform.step() {
            Ok(true) => {}
            Ok(false) => return (Err("the world stopped".into()), true),
            Err(error) => return (Err(error.to_string()), true),
        }
    }
    let observed = features
        .observe(&platform.world())
        .map_err(|e| e.to_string())
        .map(|observation| Observed {
            observation,
            time: platform.pl().time(),
            ticks: platform.pl().ticks(),
            warnings: match (warnings(platform), before) {
                (Some(now), Some(before)) => now.since(&before),
                _ => Vec::new(),
            },
        });
    let ended = observed.is_err();
    (observed, ended)
}
