//! The native half of yarok's Python package (`yarok._native`): `World`, a world driven step
//! by step from Python, `Worlds`, several stepped at once on threads of their own, and `run`,
//! a bundled world's demo behaviour run to its end (recording demonstrations). The Gymnasium environments are Python, over these.

mod features;
mod observation;
mod run;
mod worker;
mod world;
mod worlds;

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
    module.add("DIGIT_WORLD_START_REGION", demos::START_REGION)?;
    module.add("DIGIT_WORLD_START_YAW", demos::START_YAW)?;
    Ok(())
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

/// yarok's error text as a Python exception.
fn error(text: String) -> PyErr {
    YarokError::new_err(text)
}
