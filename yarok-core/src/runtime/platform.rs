//! [`Platform`]: binds the components, then ticks the backend and runs behaviours, components'
//! tasks and plugins on the ticks until the behaviours end; then stops everything safely.

use std::cell::RefCell;
use std::future::Future;
use std::pin::Pin;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use tokio::task::LocalSet;

use super::executor::{Executor, Owner};
use super::interrupt::Interrupt;
use super::pl::PlParts;
use super::{BehaviourResult, Pl, PlatformBuilder, Plugin, RuntimeError, World};
use crate::component::{
    Backend, BindContext, Binder, Handles, Lifecycle, NamedActuation, NamedCommand, NamedState,
    Probe, StopAction, TickStep,
};
use crate::compose::{Composition, Instance};
use crate::config::{ConfigOrigins, PlatformSettings, Settings};
use crate::time::Clock;
use crate::value::Config;

/// A behaviour's future.
type Behaviour = Pin<Box<dyn Future<Output = BehaviourResult>>>;
/// A behaviour not started yet, with its name.
pub(super) type BehaviourFactory = (String, Box<dyn FnOnce(Pl) -> Behaviour>);

/// How often an unpaced run looks whether it is time to let other tokio tasks (the
/// application's, I/O) run: every this many ticks...
const YIELD_CHECK_TICKS: u64 = 64;
/// ...it yields to the tokio scheduler when this much wall time passed since it last did, so
/// that they are served without slowing stepping. (Ctrl-C needs none: it sets the stop flag, read
/// every tick.)
const YIELD_EVERY: std::time::Duration = std::time::Duration::from_millis(1);

/// What the builder checked and made.
pub(super) struct Prepared {
    pub(super) environment: &'static str,
    pub(super) backend: Rc<dyn Backend>,
    pub(super) composition: Composition,
    pub(super) settings: Settings,
    pub(super) platform: PlatformSettings,
    pub(super) behaviour: Config,
    pub(super) plugins: Vec<Box<dyn Plugin>>,
    pub(super) behaviours: Vec<BehaviourFactory>,
    pub(super) stop: Arc<AtomicBool>,
    pub(super) ctrl_c: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Built,
    Running,
    Ended,
}

/// A platform: world composed, backend made; components bind when it starts.
///
/// Run it whole with [`Platform::run`] (or [`Platform::run_local`] inside an application's
/// tokio runtime), or tick by tick with [`Platform::step`] to assert between ticks.
pub struct Platform {
    environment: &'static str,
    pl: Pl,
    clock: Clock,
    backend: Rc<dyn Backend>,
    composition: Composition,
    settings: Settings,
    platform: PlatformSettings,
    plugins: Vec<Box<dyn Plugin>>,
    behaviours: Vec<BehaviourFactory>,
    handles: Rc<RefCell<Handles>>,
    lifecycle: Rc<RefCell<Lifecycle>>,
    ticks: Vec<(String, tracing::Span, TickStep)>,
    probes: Vec<Probe>,
    states: Vec<NamedState>,
    commands: Vec<NamedCommand>,
    actuations: Vec<NamedActuation>,
    executor: Executor,
    phase: Phase,
    ctrl_c: bool,
    interrupt: Option<Interrupt>,
    /// Whether ticks are paced to the wall clock (hardware, or `[platform] realtime`).
    paced: bool,
    /// When an unpaced run last let other tokio tasks run.
    yielded: std::time::Instant,
    /// The stop flag (`pl.stop()`, [`Platform::stop_flag`], Ctrl-C), read every tick.
    stop: Arc<AtomicBool>,
    started: Option<tokio::time::Instant>,
    stepper: Option<(tokio::runtime::Runtime, LocalSet)>,
}

impl std::fmt::Debug for Platform {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Platform")
            .field("pl", &self.pl)
            .field("phase", &self.phase)
            .finish()
    }
}

impl Platform {
    /// A builder with no world and no environments; `yarok::platform()` registers yarok's.
    pub fn builder() -> PlatformBuilder {
        PlatformBuilder::new()
    }

    pub(super) fn new(prepared: Prepared) -> Self {
        let clock = Clock::new(prepared.backend.time(), prepared.backend.timestep());
        let handles = Rc::new(RefCell::new(Handles::new(
            prepared
                .composition
                .instances
                .iter()
                .map(|i| (i.path.clone(), i.component)),
        )));
        let executor = Executor::new(clock.clone());
        let stop = Arc::clone(&prepared.stop);
        let paced = prepared.platform.realtime || prepared.backend.paced();
        let lifecycle = Rc::new(RefCell::new(Lifecycle::default()));
        let pl = Pl::new(
            clock.clone(),
            PlParts {
                environment: prepared.environment.to_owned(),
                handles: Rc::clone(&handles),
                behaviour: prepared.behaviour,
                stop: prepared.stop,
                keeps_happenings: !prepared.plugins.is_empty(),
                shard: prepared.platform.shard,
                backend: Rc::clone(&prepared.backend),
                lifecycle: Rc::clone(&lifecycle),
            },
        );
        Self {
            environment: prepared.environment,
            pl,
            clock,
            backend: prepared.backend,
            composition: prepared.composition,
            settings: prepared.settings,
            platform: prepared.platform,
            plugins: prepared.plugins,
            behaviours: prepared.behaviours,
            handles,
            lifecycle,
            ticks: Vec::new(),
            probes: Vec::new(),
            states: Vec::new(),
            commands: Vec::new(),
            actuations: Vec::new(),
            executor,
            phase: Phase::Built,
            ctrl_c: prepared.ctrl_c,
            interrupt: None,
            paced,
            yielded: std::time::Instant::now(),
            stop,
            started: None,
            stepper: None,
        }
    }

    /// The platform handle (time, waits, components once bound).
    pub fn pl(&self) -> &Pl {
        &self.pl
    }

    /// The composed world.
    pub fn composition(&self) -> &Composition {
        &self.composition
    }

    /// A flag that stops the platform after the current tick when set, from any thread.
    pub fn stop_flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.stop)
    }

    /// Runs on a new single-threaded tokio runtime until the behaviours finish, one fails, a
    /// plugin or a component fails, the platform is stopped, or Ctrl-C; then stops everything
    /// (see [`Platform::run_local`]).
    ///
    /// # Errors
    ///
    /// The first binding, behaviour, plugin, component or backend error;
    /// [`RuntimeError::Interrupted`] on Ctrl-C, `SIGTERM` or `SIGHUP`.
    pub fn run(self) -> Result<(), RuntimeError> {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .map_err(RuntimeError::Start)?;
        LocalSet::new().block_on(&runtime, self.run_local())
    }

    /// Runs inside the caller's tokio runtime (current-thread, or a `LocalSet`): binds the
    /// components, runs until the end as [`Platform::run`] does, then shuts down: pending waits
    /// fail with [`WaitError::Stopped`](crate::time::WaitError::Stopped) so behaviours can
    /// clean up, plugins end, and the components' stop actions run in reverse binding order,
    /// each bounded in time.
    ///
    /// # Errors
    ///
    /// As [`Platform::run`]; a stop action's failure when nothing failed before.
    ///
    /// # Cancel safety
    ///
    /// Not cancel safe: dropping the future before it completes skips the stop actions. Stop
    /// the platform through its [stop flag](Platform::stop_flag) instead.
    pub async fn run_local(mut self) -> Result<(), RuntimeError> {
        // The whole loop is one poll of this future between yields: tokio's per-poll budget
        // would otherwise run out across ticks and stall the tasks' tokio resources.
        let result = tokio::task::unconstrained(self.run_to_end()).await;
        self.shutdown(result).await
    }

    async fn run_to_end(&mut self) -> Result<(), RuntimeError> {
        self.start().await?;
        let mut goes_on = self.goes_on()?;
        while goes_on {
            // Most unpaced ticks need no `.await`: they skip the asynchronous pacing.
            if (self.paced || self.due_to_yield()) && !self.pace().await? {
                break;
            }
            goes_on = self.tick()?;
        }
        Ok(())
    }

    /// Advances one tick — starting the platform (binding every component, starting plugins and
    /// behaviours) the first time — and returns whether the run goes on. When it ends (the
    /// behaviours returned, the platform was stopped, or something failed) the platform shuts
    /// down as [`Platform::run_local`] does. For tests that assert between ticks; runs its own
    /// tokio runtime, so call it outside async code.
    ///
    /// # Errors
    ///
    /// As [`Platform::run`].
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_core::component::{Component, Declaration, Mock, MockBackend};
    /// use yarok_core::runtime::Platform;
    ///
    /// struct Empty;
    /// impl Component for Empty {
    ///     fn declaration() -> Declaration {
    ///         Declaration::new("empty").template("<mujoco/>")
    ///     }
    /// }
    ///
    /// let mut platform = Platform::builder()
    ///     .world::<Empty>()
    ///     .environment("mock")
    ///     .backend::<Mock>(|_, _| Ok(MockBackend::new(0.5, false)))
    ///     .behaviour(|pl| async move {
    ///         pl.wait_seconds(1.0).await?;
    ///         Ok(())
    ///     })
    ///     .build()?;
    /// assert!(platform.step()?);
    /// assert_eq!(platform.pl().time(), 0.5);
    /// assert!(!platform.step()?, "the behaviour returned on the second tick");
    /// assert_eq!(platform.pl().ticks(), 2);
    /// # Ok::<(), yarok_core::runtime::RuntimeError>(())
    /// ```
    pub fn step(&mut self) -> Result<bool, RuntimeError> {
        if self.phase == Phase::Ended {
            return Ok(false);
        }
        let (runtime, local) = match self.stepper.take() {
            Some(stepper) => stepper,
            None => (
                tokio::runtime::Builder::new_current_thread()
                    .enable_all()
                    .build()
                    .map_err(RuntimeError::Start)?,
                LocalSet::new(),
            ),
        };
        let result = local.block_on(
            &runtime,
            tokio::task::unconstrained(async {
                if self.phase == Phase::Built {
                    self.start().await?;
                }
                self.advance().await
            }),
        );
        let result = match result {
            Ok(true) => Ok(true),
            ended => local
                .block_on(&runtime, self.shutdown(ended.map(drop)))
                .map(|()| false),
        };
        self.stepper = Some((runtime, local));
        result
    }

    /// What `instance`'s interface is bound with.
    fn bind_context(&self, instance: &Instance, origins: &Rc<ConfigOrigins>) -> BindContext {
        BindContext {
            environment: self.environment,
            path: instance.path.clone(),
            config: instance.config.clone(),
            names: instance.names.clone(),
            settings: self
                .settings
                .interfaces
                .get(&instance.path)
                .cloned()
                .unwrap_or_default(),
            origins: Rc::clone(origins),
            backend: Rc::clone(&self.backend),
            handles: Rc::clone(&self.handles),
            clock: self.clock.clone(),
            seed: self.platform.seed_for(&instance.path),
            lifecycle: Rc::clone(&self.lifecycle),
        }
    }

    /// Checks every component's interface, binds them (children first), then starts plugins
    /// and behaviours.
    async fn start(&mut self) -> Result<(), RuntimeError> {
        self.phase = Phase::Running;
        let origins = Rc::new(self.settings.origins.clone());
        let binders: Vec<(&Instance, Binder)> = self
            .composition
            .instances
            .iter()
            .rev()
            .filter_map(|instance| Some((instance, instance.component.binder(self.environment)?)))
            .collect();
        for (instance, binder) in &binders {
            (binder.check)(self.bind_context(instance, &origins))?;
        }
        for (instance, binder) in binders {
            let handle = (binder.bind)(self.bind_context(instance, &origins)).await?;
            self.handles.borrow_mut().insert(&instance.path, handle);
        }
        let tasks = {
            let mut lifecycle = self.lifecycle.borrow_mut();
            self.ticks = std::mem::take(&mut lifecycle.ticks);
            self.probes = std::mem::take(&mut lifecycle.probes);
            self.states = std::mem::take(&mut lifecycle.states);
            self.commands = std::mem::take(&mut lifecycle.commands);
            self.actuations = std::mem::take(&mut lifecycle.actuations);
            std::mem::take(&mut lifecycle.tasks)
        };
        self.backend.remember_start();
        for (component, task) in tasks {
            self.executor.spawn(Owner::Component(component), task);
        }
        let (plugins, world) = self.plugins_and_world();
        for plugin in plugins {
            plugin
                .start(&world)
                .map_err(|source| RuntimeError::Plugin {
                    name: plugin.name(),
                    source,
                })?;
        }
        for (index, (name, behaviour)) in
            std::mem::take(&mut self.behaviours).into_iter().enumerate()
        {
            let future = behaviour(self.pl.clone());
            self.executor
                .spawn(Owner::Behaviour { index, name }, future);
        }
        self.interrupt = self.ctrl_c.then(|| Interrupt::listen(&self.stop));
        self.started = Some(tokio::time::Instant::now());
        self.executor.poll()
    }

    /// Whether the run goes on: behaviours are pending and nobody asked to stop.
    ///
    /// # Errors
    ///
    /// [`RuntimeError::Interrupted`] when a signal asked.
    fn goes_on(&self) -> Result<bool, RuntimeError> {
        if !self.stop.load(std::sync::atomic::Ordering::Relaxed) {
            return Ok(!self.executor.behaviours_done());
        }
        if let Some(signal) = self.interrupt.as_ref().and_then(Interrupt::signal) {
            return Err(RuntimeError::Interrupted { signal });
        }
        Ok(false)
    }

    /// One tick, paced; whether the run goes on.
    async fn advance(&mut self) -> Result<bool, RuntimeError> {
        Ok(self.pace().await? && self.tick()?)
    }

    /// Whether the next unpaced tick is one on which other tokio tasks get their turn.
    fn due_to_yield(&self) -> bool {
        (self.clock.ticks() + 1).is_multiple_of(YIELD_CHECK_TICKS)
            && self.yielded.elapsed() >= YIELD_EVERY
    }

    /// Waits until the next tick is due — serving I/O meanwhile — on hardware or in real time,
    /// or yields to tokio now and then; whether the run goes on.
    async fn pace(&mut self) -> Result<bool, RuntimeError> {
        if !self.goes_on()? {
            return Ok(false);
        }
        if self.paced {
            // On hardware a tick happens at its due time, so tick n reads time n·timestep.
            let started = self.started.unwrap_or_else(tokio::time::Instant::now);
            let ticks = self.clock.ticks() + 1;
            let due =
                started + std::time::Duration::from_secs_f64(ticks as f64 * self.clock.timestep());
            self.executor.serve_until(due).await?;
            return self.goes_on();
        }
        if self.due_to_yield() {
            tokio::task::yield_now().await;
            self.yielded = std::time::Instant::now();
        }
        Ok(true)
    }

    /// Steps the backend, advances the clock to the time the step reached, steps the components
    /// and the plugins (which so read the tick they see), then runs what the tick woke; whether
    /// the run goes on.
    // Inlined into the run loop, as the executor's tick is into it: each call made after a
    // simulation step costs several ns (measured with `cargo bench --bench platform`).
    #[inline(always)]
    fn tick(&mut self) -> Result<bool, RuntimeError> {
        // The hot path is kept small: after a step, little of it is still in the CPU's caches.
        let time = match self.backend.step() {
            Ok(time) => time,
            Err(source) => return Err(self.step_failed(source)),
        };
        self.clock.advance(time);
        if !self.ticks.is_empty() {
            self.tick_interfaces()?;
        }
        if !self.plugins.is_empty() {
            self.step_plugins()?;
            self.pl.clear_happenings();
        }
        if !self.executor.tick() {
            self.executor.failure()?;
        }
        self.goes_on()
    }

    #[cold]
    fn step_failed(&self, source: crate::BoxError) -> RuntimeError {
        RuntimeError::Step {
            environment: self.environment.to_owned(),
            source,
        }
    }

    #[inline(never)]
    fn tick_interfaces(&mut self) -> Result<(), RuntimeError> {
        for (component, span, step) in &mut self.ticks {
            let _entered = span.enter();
            step().map_err(|source| RuntimeError::Interface {
                component: component.clone(),
                source,
            })?;
        }
        Ok(())
    }

    #[inline(never)]
    fn step_plugins(&mut self) -> Result<(), RuntimeError> {
        let (plugins, world) = self.plugins_and_world();
        for plugin in plugins {
            plugin.step(&world).map_err(|source| RuntimeError::Plugin {
                name: plugin.name(),
                source,
            })?;
        }
        Ok(())
    }

    /// The world as plugins see it, between ticks: for a driver that steps the platform with
    /// [`Platform::step`] and reads or commands the world in between (a Gymnasium
    /// environment). Probes, states, commands and actuations are listed once the platform
    /// has started (after the first step).
    pub fn world(&self) -> World<'_> {
        World {
            pl: &self.pl,
            backend: self.backend.as_ref(),
            composition: &self.composition,
            settings: &self.settings,
            probes: &self.probes,
            states: &self.states,
            commands: &self.commands,
            actuations: &self.actuations,
        }
    }

    /// The plugins, and the world they see.
    fn plugins_and_world(&mut self) -> (&mut [Box<dyn Plugin>], World<'_>) {
        let world = World {
            pl: &self.pl,
            backend: self.backend.as_ref(),
            composition: &self.composition,
            settings: &self.settings,
            probes: &self.probes,
            states: &self.states,
            commands: &self.commands,
            actuations: &self.actuations,
        };
        (&mut self.plugins, world)
    }

    /// Ends the run: behaviours' last poll, plugins' end, stop actions, the backend's stop.
    /// Returns `result`, or the first failure of the shutdown when `result` is `Ok`.
    async fn shutdown(&mut self, result: Result<(), RuntimeError>) -> Result<(), RuntimeError> {
        if self.phase == Phase::Ended {
            return result;
        }
        self.phase = Phase::Ended;
        let mut result = result;
        self.clock.stop();
        self.executor.finish();
        let (plugins, world) = self.plugins_and_world();
        for plugin in plugins {
            if let Err(source) = plugin.end(&world) {
                let error = RuntimeError::Plugin {
                    name: plugin.name(),
                    source,
                };
                keep_first(&mut result, error);
            }
        }
        let stops = std::mem::take(&mut self.lifecycle.borrow_mut().stops);
        for stop in stops.into_iter().rev() {
            if let Err(error) = run_stop_action(stop).await {
                keep_first(&mut result, error);
            }
        }
        self.backend.stop();
        self.interrupt = None;
        result
    }
}

/// Keeps the first error; reports later ones, which would otherwise be lost.
fn keep_first(result: &mut Result<(), RuntimeError>, error: RuntimeError) {
    if result.is_ok() {
        *result = Err(error);
    } else {
        tracing::error!("during shutdown: {error}");
    }
}

async fn run_stop_action(stop: StopAction) -> Result<(), RuntimeError> {
    let failed = |source| RuntimeError::Stop {
        component: stop.component.clone(),
        source,
    };
    let Ok(limit) = std::time::Duration::try_from_secs_f64(stop.seconds) else {
        return Err(failed(
            format!("invalid stop time {} s", stop.seconds).into(),
        ));
    };
    match tokio::time::timeout(limit, stop.action).await {
        Ok(Ok(())) => Ok(()),
        Ok(Err(source)) => Err(failed(source)),
        Err(_) => Err(failed(
            format!("its stop action did not finish within {} s", stop.seconds).into(),
        )),
    }
}

impl Drop for Platform {
    /// A platform stepped with [`Platform::step`] and dropped before its end still runs its
    /// shutdown, so devices are left safe.
    fn drop(&mut self) {
        if self.phase != Phase::Running {
            return;
        }
        if let Some((runtime, local)) = self.stepper.take() {
            let _dropped_mid_run = local.block_on(&runtime, self.shutdown(Ok(())));
        }
    }
}
