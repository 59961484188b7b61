//! The native half of yarok's Python package (`yarok._native`): `World`, a world driven step
//! by step from Python, `Worlds`, several stepped at once on threads of their own, and `run`,
//! a bundled world's demo behaviour run to its end (recording demonstrations). The Gymnasium
//! environments are Python, over these.
//!
//! As a library, it builds the extension module of your own crate: [`module!`] exports your
//! worlds and components ([`Exports`]) to Python beside the bundled ones.

mod boundary;
mod exports;
mod features;
mod observation;
mod run;
mod worker;
mod world;
mod worlds;

pub use exports::Exports;
/// The PyO3 this crate is built with, for [`module!`]'s expansion.
pub use pyo3;

use pyo3::prelude::*;
use yarok::components::demos;

/// Defines the Python extension module `$name` of your own crate: yarok's `World`, `Worlds`,
/// `run` and `YarokError`, opening the bundled worlds and those `$exports` (an [`Exports`])
/// names. Build the crate as a `cdylib` with maturin (its `module-name` being `$name`), install
/// it beside the `yarok` package, and give its name to a task
/// (`yarok.Task(world="showroom", extension="my_turntable")`) to make your world a Gymnasium
/// environment. Depend on this crate as `yarok-py` (the expansion names it `yarok_py`).
///
/// ```ignore
/// yarok_py::module!(my_turntable, yarok_py::Exports::new().world::<Showroom>());
/// ```
///
/// `examples/own_crate/py` is such a module, built and tested by CI.
#[macro_export]
macro_rules! module {
    ($name:ident, $exports:expr) => {
        #[$crate::pyo3::pymodule]
        #[pyo3(crate = "::yarok_py::pyo3")]
        fn $name(
            module: &$crate::pyo3::Bound<'_, $crate::pyo3::types::PyModule>,
        ) -> $crate::pyo3::PyResult<()> {
            $crate::export(module, $exports)
        }
    };
}

/// Fills `module`, the extension module of your own crate, with yarok's Python API opening
/// the bundled worlds and those of `exports` (what [`module!`] expands to). It imports the
/// `yarok` package first: errors are raised as its `YarokError`, and a MuJoCo shipped inside
/// its wheel is used.
pub fn export(module: &Bound<'_, PyModule>, exports: Exports) -> PyResult<()> {
    let py = module.py();
    let yarok_package = py.import("yarok")?;
    let yarok_error = yarok_package.getattr("YarokError")?;
    boundary::raise_as(yarok_error.cast::<pyo3::types::PyType>()?);
    module.add("YarokError", yarok_error)?;
    let bundled_mujoco =
        std::path::Path::new(&yarok_package.getattr("__file__")?.extract::<String>()?)
            .with_file_name("mujoco");
    if bundled_mujoco.is_dir() {
        yarok::mjc::use_bundled_mujoco(bundled_mujoco);
    }
    exports::record(exports).map_err(boundary::error)?;
    add_api(module)?;
    let fork_hook = module.getattr("after_fork_in_child")?;
    let keywords = pyo3::types::PyDict::new(py);
    keywords.set_item("after_in_child", fork_hook)?;
    py.import("os")?
        .getattr("register_at_fork")?
        .call((), Some(&keywords))?;
    Ok(())
}

/// yarok's own extension module, `yarok._native`.
#[pymodule(name = "_native")]
fn native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("YarokError", module.py().get_type::<boundary::YarokError>())?;
    add_api(module)?;
    module.add_function(wrap_pyfunction!(use_bundled_mujoco, module)?)?;
    module.add("DIGIT_WORLD_START_REGION", demos::START_REGION)?;
    module.add("DIGIT_WORLD_START_YAW", demos::START_YAW)?;
    module.add(
        "UR_JOINT_SPEED",
        yarok::components::robots::ur::UR_JOINT_SPEED,
    )?;
    Ok(())
}

/// What every extension module holds: the classes and functions that open worlds.
fn add_api(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_class::<features::Features>()?;
    module.add_class::<world::World>()?;
    module.add_class::<worlds::Worlds>()?;
    module.add_function(wrap_pyfunction!(run::run, module)?)?;
    module.add_function(wrap_pyfunction!(after_fork_in_child, module)?)?;
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
