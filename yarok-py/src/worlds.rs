//! [`Worlds`]: several copies of a world, each on its own thread, stepped at once.

use std::sync::Mutex;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::boundary::{error, exclusive, interrupted};
use crate::features::Features;
use crate::observation;
use crate::worker::{Observed, Worker, WorldInfo, WorldSpec};
use crate::world::{BodyPlacements, placements, start, ticks_for};

/// What sends one world its request.
type SendRequest = Box<dyn FnOnce(&Worker) -> Result<(), String> + Send>;

/// `count` copies of a world (as [`World`](crate::world::World) takes it), each on a thread of
/// its own: a step sends every world its action, then waits for all without the GIL, so N
/// worlds step on N cores.
#[pyclass(module = "yarok._native")]
pub(crate) struct Worlds {
    workers: Mutex<Vec<Worker>>,
    info: WorldInfo,
    /// What MuJoCo warned of in each world's last steps.
    warnings: Mutex<Vec<Vec<&'static str>>>,
}

impl Worlds {
    /// Sends each chosen world its request, then takes every reply, in order.
    fn exchange<'py>(
        &self,
        py: Python<'py>,
        requests: Vec<(usize, SendRequest)>,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let mut guard = exclusive(&self.workers, "the worlds")?;
        let workers: &mut Vec<Worker> = &mut guard;
        let count = workers.len();
        if let Some((index, _)) = requests.iter().find(|(index, _)| *index >= count) {
            return Err(error(format!("no world {index}: there are {count}")));
        }
        let indices: Vec<usize> = requests.iter().map(|(index, _)| *index).collect();
        let mut pending = None;
        let replies = py.detach(|| {
            let mut sent = Vec::with_capacity(requests.len());
            for (index, send) in requests {
                send(&workers[index])?;
                sent.push(index);
            }
            let mut replies: Vec<Observed> = Vec::with_capacity(sent.len());
            for index in sent {
                match workers[index].reply(&mut interrupted(&mut pending)) {
                    Some(Ok(observed)) => replies.push(observed),
                    Some(Err(text)) => return Err(format!("world {index}: {text}")),
                    None => return Err("the worlds were stopped".into()),
                }
            }
            Ok(replies)
        });
        if let Some(interrupt) = pending {
            // Every world stops at its next tick, then each is waited for.
            for worker in workers.iter() {
                worker.interrupt();
            }
            for worker in workers.iter_mut() {
                let _ = py.detach(|| worker.close());
            }
            return Err(interrupt);
        }
        let replies = replies.map_err(error)?;
        let mut warnings = self.warnings.lock().map_err(|_| error("poisoned".into()))?;
        for (index, observed) in indices.iter().zip(&replies) {
            warnings[*index] = observed.warnings.clone();
        }
        drop(warnings);
        replies
            .into_iter()
            .map(|observed| observation::to_dict(py, &self.info, observed))
            .collect()
    }
}

#[pymethods]
impl Worlds {
    #[new]
    #[pyo3(signature = (world, count, env = "sim", settings = Vec::new(), config = Vec::new(), cameras = Vec::new(), camera_size = (84, 84)))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        world: String,
        count: usize,
        env: &str,
        settings: Vec<String>,
        config: Vec<String>,
        cameras: Vec<String>,
        camera_size: (u32, u32),
    ) -> PyResult<Self> {
        if count == 0 {
            return Err(error("a vector of worlds needs at least one".into()));
        }
        let spec = WorldSpec {
            world,
            environment: env.to_owned(),
            settings,
            configs: config,
            cameras,
            camera_size: [camera_size.0, camera_size.1],
        };
        let workers = (0..count)
            .map(|_| start(py, spec.clone()))
            .collect::<PyResult<Vec<_>>>()?;
        let info = workers[0].info().clone();
        Ok(Self {
            warnings: Mutex::new(vec![Vec::new(); workers.len()]),
            workers: Mutex::new(workers),
            info,
        })
    }

    /// Begins an episode in each world given, `[(index, episode, placements), …]`; their
    /// observations, in the same order.
    fn reset<'py>(
        &self,
        py: Python<'py>,
        worlds: Vec<(usize, u64, BodyPlacements)>,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let requests = worlds
            .into_iter()
            .map(|(index, episode, given)| {
                let placements = placements(given);
                let send: SendRequest =
                    Box::new(move |worker| worker.send_reset(episode, placements));
                (index, send)
            })
            .collect();
        self.exchange(py, requests)
    }

    /// Sets each world's action (`None`: keep its targets) and advances every world
    /// `seconds`; their observations, in order. Every action is checked first: one refused
    /// raises, naming its world, and no world advances.
    fn advance<'py>(
        &self,
        py: Python<'py>,
        seconds: f64,
        actions: Vec<Option<Vec<f64>>>,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let ticks = ticks_for(seconds, self.info.timestep)?;
        for (index, action) in actions.iter().enumerate() {
            if let Some(action) = action {
                self.info.check_action(action).map_err(|refused| {
                    error(format!("world {index}: {refused}; no world was advanced"))
                })?;
            }
        }
        let requests = actions
            .into_iter()
            .enumerate()
            .map(|(index, action)| {
                let send: SendRequest = Box::new(move |worker| worker.send_step(action, ticks));
                (index, send)
            })
            .collect();
        self.exchange(py, requests)
    }

    /// Stops every world, devices left safe; raises the first failure.
    fn close(&self, py: Python<'_>) -> PyResult<()> {
        let mut guard = exclusive(&self.workers, "the worlds")?;
        let workers: &mut Vec<Worker> = &mut guard;
        let outcomes: Vec<Result<(), String>> =
            py.detach(|| workers.iter_mut().map(Worker::close).collect());
        outcomes
            .into_iter()
            .collect::<Result<(), String>>()
            .map_err(error)
    }

    /// The worlds' features: what their observations and actions hold.
    #[getter]
    fn features(&self) -> Features {
        Features(self.info.clone())
    }

    /// What MuJoCo warned of while each world was last stepped, in words: empty where the
    /// steps went as they should.
    #[getter]
    fn warnings(&self) -> PyResult<Vec<Vec<&'static str>>> {
        Ok(self
            .warnings
            .lock()
            .map_err(|_| error("poisoned".into()))?
            .clone())
    }

    /// How many worlds.
    fn __len__(&self) -> PyResult<usize> {
        Ok(exclusive(&self.workers, "the worlds")?.len())
    }
}
