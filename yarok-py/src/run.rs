//! `yarok.run`: a bundled world with one of its demo behaviours, run to its end as `yarok run`
//! runs it — how Python records demonstrations (`dataset=`) for learning.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{RecvTimeoutError, channel};

use pyo3::prelude::*;
use yarok::core::suggest::did_you_mean;

use crate::boundary::{error, interrupted};
use crate::worker::{POLL, bundled, starting};

/// Runs the bundled world `world` with its demo behaviour `behaviour` (its default when
/// `None`; `yarok run --list` names them), in `env`, with the command line's settings
/// (`settings=["behaviour/episodes=20"]`, `config=["run.toml"]`), until the behaviour ends.
/// `dataset` records the run as a LeRobot dataset in that folder (`yarok run --dataset`),
/// with the features the Gymnasium environments observe.
///
/// The run happens on a thread of its own without the GIL; Ctrl-C stops it (devices left
/// safe, recordings finished) and raises `KeyboardInterrupt`. A failed behaviour raises
/// `YarokError` in yarok's words.
#[pyfunction]
#[pyo3(signature = (world, behaviour = None, env = "sim", settings = Vec::new(), config = Vec::new(), dataset = None))]
pub(crate) fn run(
    py: Python<'_>,
    world: &str,
    behaviour: Option<&str>,
    env: &str,
    settings: Vec<String>,
    config: Vec<String>,
    dataset: Option<PathBuf>,
) -> PyResult<()> {
    starting().map_err(error)?;
    let demo = bundled(world).map_err(error)?;
    let chosen = demo.behaviour(behaviour).ok_or_else(|| {
        let names: Vec<&str> = demo.behaviours.iter().map(|b| b.name).collect();
        let asked = behaviour.unwrap_or_default();
        error(format!(
            "{world} has no behaviour {asked:?}{} (its behaviours: {})",
            did_you_mean(asked, names.iter().copied()),
            names.join(", ")
        ))
    })?;
    let mut args = vec!["--env".to_owned(), env.to_owned()];
    if let Some(folder) = dataset {
        let folder = folder.to_string_lossy().into_owned();
        args.extend([
            "--set".to_owned(),
            format!("plugins/dataset/path={folder:?}"),
        ]);
    }
    args.extend(settings.into_iter().flat_map(|s| ["--set".to_owned(), s]));
    args.extend(config.into_iter().flat_map(|c| ["--config".to_owned(), c]));
    let world_type = demo.world;
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let (done, outcome) = channel();
    let thread = std::thread::Builder::new()
        .name(format!("yarok run {world}"))
        .spawn(move || {
            let ran = chosen
                .install(yarok::platform().world_type(world_type))
                .args(args)
                .map_err(|e| e.to_string())
                .and_then(|builder| {
                    builder
                        .stop_flag(flag)
                        .ctrl_c(false)
                        .run()
                        .map_err(|e| e.to_string())
                });
            let _ = done.send(ran);
        })
        .map_err(|e| error(format!("cannot start the run's thread: {e}")))?;
    let mut pending = None;
    let waiting_for = &mut pending;
    let ran = py.detach(move || {
        let mut interrupted = interrupted(waiting_for);
        loop {
            match outcome.recv_timeout(POLL) {
                Ok(ran) => break ran,
                Err(RecvTimeoutError::Timeout) if interrupted() => {
                    stop.store(true, Ordering::Relaxed);
                    break outcome
                        .recv()
                        .unwrap_or_else(|_| Err("the run's thread ended".into()));
                }
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => break Err("the run's thread ended".into()),
            }
        }
    });
    let joined = thread.join();
    if let Some(interrupt) = pending {
        return Err(interrupt);
    }
    joined.map_err(|_| error("the run's thread panicked".into()))?;
    ran.map_err(error)
}
