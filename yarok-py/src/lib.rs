//! The native half of yarok's Python package (`yarok._native`): `World`, a world driven step
//! by step from Python, `Worlds`, several stepped at once on threads of their own, and `run`,
//! a bundled world's demo behaviour run to its end (recording demonstrations). The Gymnasium environments are Python, over these.

mod features;
mod observation;
mod run;
mod worker;
mod world;
mod worlds;

use std::sync::{Mutex, MutexGuard, TryLockError};

use pyo3::prelude::*;
use yarok::components::demos;

pyo3::create_exception!(
    _native,
    YarokError,
    pyo3::exceptions::PyRuntimeError,
    "What yarok refused or what failed in a world, in yarok's words."
);

#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("YarokError", module.py().get_type::<YarokError>())?;
    module.add_class::<features::Features>()?;
    module.add_class::<world::World>()?;
    module.add_class::<worlds::Worlds>()?;
    module.add_function(wrap_pyfunction!(run::run, module)?)?;
    module.add_function(wrap_pyfunction!(after_fork_in_child, module)?)?;
    module.add_function(wrap_pyfunction!(use_bundled_mujoco, module)?)?;
    module.add("DIGIT_WORLD_START_REGION", demos::START_REGION)?;
    module.add("DIGIT_WORLD_START_YAW", demos::START_YAW)?;
    module.add(
        "UR_JOINT_SPEED",
        yarok::components::robots::ur::UR_JOINT_SPEED,
    )?;
    Ok(())
}

/// Makes `dir`, the MuJoCo folder a wheel ships inside the package, where MuJoCo is found
/// (unless `MUJOCO_DIR` is set); called on import. Whether it took effect (not once a world
/// has opened MuJoCo).
#[pyfunction]
fn use_bundled_mujoco(dir: std::path::PathBuf) -> bool {
    yarok::mjc::use_bundled_mujoco(dir)
}

/// Called in a forked child (registered with `os.register_at_fork` on import): a world made
/// in a fork of a process that had worlds is refused at once, naming the start method to use,
/// instead of hanging on the parent's rendering locks.
#[pyfunction]
fn after_fork_in_child() {
    worker::forked();
}

/// Whether Ctrl-C (or another signal Python handles) arrived: checked with the GIL, while a
/// world works without it. The exception is kept to be raised.
fn interrupted(pending: &mut Option<PyErr>) -> impl FnMut() -> bool + '_ {
    move || {
        Python::attach(|py| match py.check_signals() {
            Ok(()) => false,
            Err(error) => {
                *pending = Some(error);
                true
            }
        })
    }
}

/// The lock of a world (or worlds) a call works on, taken at once: a world stepped from two
/// Python threads raises in the second (it would wait with the GIL held for the first, which
/// needs the GIL to finish: a deadlock).
fn exclusive<'a, T>(lock: &'a Mutex<T>, what: &str) -> PyResult<MutexGuard<'a, T>> {
    lock.try_lock().map_err(|failure| match failure {
        TryLockError::WouldBlock => error(format!(
            "{what} is busy with a call from another thread: step a world from one thread at a \
             time (give each thread a world of its own, or use yarok.Worlds)"
        )),
        TryLockError::Poisoned(_) => error(format!("{what} was left broken by an earlier failure")),
    })
}

/// yarok's error text as a Python exception.
fn error(text: String) -> PyErr {
    YarokError::new_err(text)
}
