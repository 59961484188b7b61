//! The native half of yarok's Python package (`yarok._native`): `World`, a world driven step
//! by step from Python, `Worlds`, several stepped at once on threads of their own, and `run`,
//! a bundled world's demo behaviour run to its end (recording demonstrations). The Gymnasium environments are Python, over these.

mod boundary;
mod features;
mod observation;
mod run;
mod worker;
mod world;
mod worlds;

use pyo3::prelude::*;
use yarok::components::demos;

#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("YarokError", module.py().get_type::<boundary::YarokError>())?;
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
