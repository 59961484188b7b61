//! [`World`]: one yarok world driven from Python, step by step.

use std::sync::Mutex;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::boundary::{error, exclusive, interrupted};
use crate::features::Features;
use crate::observation;
use crate::worker::{BodyPlacement, Worker, WorldInfo, WorldSpec};

/// A yarok world: a bundled world by its tag (`yarok run --list`) or a template file of your
/// own (`world.xml`, using the bundled components by their tags, as `yarok compose` reads it), in `sim`, `mock` or
/// `real`, with the command line's settings (`settings=["/arm/gripper/force=200"]`,
/// `config=["run.toml"]`). It runs on a thread of its own; every call waits for it without
/// the GIL, and Ctrl-C stops it (devices left safe) and raises `KeyboardInterrupt`.
///
/// Observations are dicts of numpy arrays keyed as a LeRobot dataset of the same world:
/// `observation.state` (joint positions), `observation.environment_state` (free bodies'
/// poses), `observation.images.*` (RGB, rows top first). An action is `action`'s numbers:
/// each component's targets (an arm's joints, a gripper's position 0–255).
#[pyclass(module = "yarok._native")]
pub(crate) struct World {
    worker: Mutex<Worker>,
    info: WorldInfo,
    time: Mutex<(f64, u64)>,
    warnings: Mutex<Vec<&'static str>>,
}

/// A reset's placements from Python: `[(body, (x, y, z), (qw, qx, qy, qz)), …]`.
pub(crate) type BodyPlacements = Vec<(String, [f64; 3], [f64; 4])>;

pub(crate) fn placements(given: BodyPlacements) -> Vec<BodyPlacement> {
    given
        .into_iter()
        .map(|(body, position, orientation)| BodyPlacement {
            body,
            position,
            orientation,
        })
        .collect()
}

/// Starts the world of `spec`, waiting without the GIL.
pub(crate) fn start(py: Python<'_>, spec: WorldSpec) -> PyResult<Worker> {
    let mut pending = None;
    let started = py.detach(|| Worker::start(spec, &mut interrupted(&mut pending)));
    match (started, pending) {
        (_, Some(interrupt)) => Err(interrupt),
        (started, None) => started.map_err(error),
    }
}

impl World {
    fn exchange<'py>(
        &self,
        py: Python<'py>,
        send: impl FnOnce(&Worker) -> Result<(), String> + Send,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut guard = exclusive(&self.worker, "the world")?;
        let worker: &mut Worker = &mut guard;
        let mut pending = None;
        let reply = py.detach(|| {
            send(worker)?;
            Ok::<_, String>(worker.reply(&mut interrupted(&mut pending)))
        });
        if let Some(interrupt) = pending {
            return Err(interrupt);
        }
        match reply.map_err(error)? {
            Some(Ok(observed)) => {
                *self.time.lock().map_err(|_| error("poisoned".into()))? =
                    (observed.time, observed.ticks);
                *self.warnings.lock().map_err(|_| error("poisoned".into()))? =
                    observed.warnings.clone();
                observation::to_dict(py, &self.info, observed)
            }
            Some(Err(text)) => Err(error(text)),
            None => Err(error("the world was stopped".into())),
        }
    }
}

#[pymethods]
impl World {
    #[new]
    #[pyo3(signature = (world, env = "sim", settings = Vec::new(), config = Vec::new(), cameras = Vec::new(), camera_size = (84, 84)))]
    fn new(
        py: Python<'_>,
        world: String,
        env: &str,
        settings: Vec<String>,
        config: Vec<String>,
        cameras: Vec<String>,
        camera_size: (u32, u32),
    ) -> PyResult<Self> {
        let spec = WorldSpec {
            world,
            environment: env.to_owned(),
            settings,
            configs: config,
            cameras,
            camera_size: [camera_size.0, camera_size.1],
        };
        let worker = start(py, spec)?;
        let info = worker.info().clone();
        Ok(Self {
            worker: Mutex::new(worker),
            info,
            time: Mutex::new((0.0, 0)),
            warnings: Mutex::new(Vec::new()),
        })
    }

    /// Begins episode `episode` (each number once a run): the world goes back to its start,
    /// the free bodies of `placements` are put where given, one tick passes; its observation.
    #[pyo3(signature = (episode, placements = Vec::new()))]
    fn reset<'py>(
        &self,
        py: Python<'py>,
        episode: u64,
        placements: BodyPlacements,
    ) -> PyResult<Bound<'py, PyDict>> {
        let placements = self::placements(placements);
        self.exchange(py, move |worker| worker.send_reset(episode, placements))
    }

    /// Sets `action` (if given), then advances `ticks` ticks; the observation after them.
    #[pyo3(signature = (action = None, ticks = 1))]
    fn step<'py>(
        &self,
        py: Python<'py>,
        action: Option<Vec<f64>>,
        ticks: u64,
    ) -> PyResult<Bound<'py, PyDict>> {
        self.exchange(py, move |worker| worker.send_step(action, ticks))
    }

    /// Sets `action` (if given), then advances `seconds` of platform time (whole ticks, at
    /// least one); the observation after them.
    #[pyo3(signature = (seconds, action = None))]
    fn advance<'py>(
        &self,
        py: Python<'py>,
        seconds: f64,
        action: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let ticks = ticks_for(seconds, self.info.timestep)?;
        self.exchange(py, move |worker| worker.send_step(action, ticks))
    }

    /// Sets `action` (if given), then `periods` times advances `seconds` of platform time and
    /// observes, without returning to Python in between; the last observation. An action
    /// repeated over several control periods, and how the cost of stepping from Python is
    /// measured (the same work as `periods` calls of `advance`).
    #[pyo3(signature = (periods, seconds, action = None))]
    fn advance_periods<'py>(
        &self,
        py: Python<'py>,
        periods: u64,
        seconds: f64,
        action: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        if periods == 0 {
            return Err(error("advance_periods needs at least one period".into()));
        }
        let ticks = ticks_for(seconds, self.info.timestep)?;
        self.exchange(py, move |worker| worker.send_steps(action, ticks, periods))
    }

    /// Stops the world: plugins end, devices are left safe. Raises how the run ended if it
    /// failed. Calling it again does nothing.
    fn close(&self, py: Python<'_>) -> PyResult<()> {
        let mut guard = exclusive(&self.worker, "the world")?;
        let worker: &mut Worker = &mut guard;
        py.detach(|| worker.close()).map_err(error)
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    #[pyo3(signature = (*_exception))]
    fn __exit__(
        &self,
        py: Python<'_>,
        _exception: &Bound<'_, pyo3::types::PyTuple>,
    ) -> PyResult<bool> {
        self.close(py)?;
        Ok(false)
    }

    /// The world's features: what its observations and actions hold.
    #[getter]
    fn features(&self) -> Features {
        Features(self.info.clone())
    }

    /// Platform time (seconds) at the last observation.
    #[getter]
    fn time(&self) -> PyResult<f64> {
        Ok(self.time.lock().map_err(|_| error("poisoned".into()))?.0)
    }

    /// What MuJoCo warned of while the last call stepped the world, in words (an unstable
    /// state it reset, a full contact buffer): empty when the steps went as they should.
    #[getter]
    fn warnings(&self) -> PyResult<Vec<&'static str>> {
        Ok(self
            .warnings
            .lock()
            .map_err(|_| error("poisoned".into()))?
            .clone())
    }

    /// Ticks since the start at the last observation.
    #[getter]
    fn ticks(&self) -> PyResult<u64> {
        Ok(self.time.lock().map_err(|_| error("poisoned".into()))?.1)
    }
}

/// The whole ticks `seconds` take, at least one.
pub(crate) fn ticks_for(seconds: f64, timestep: f64) -> PyResult<u64> {
    if !(seconds.is_finite() && seconds >= 0.0) {
        return Err(error(format!(
            "cannot advance {seconds} s: give a finite time, 0 or more"
        )));
    }
    Ok(((seconds / timestep).round() as u64).max(1))
}
