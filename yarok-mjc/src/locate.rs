//! Where a MuJoCo build keeps its shared library; shared by `build.rs` and the run-time loader.

use std::path::{Path, PathBuf};

/// The MuJoCo version yarok is written against.
pub(crate) const MUJOCO_VERSION: &str = "4.0.1";

/// The environment variable naming a user's own MuJoCo folder.
pub(crate) const MUJOCO_DIR_VAR: &str = "MUJOCO_DIR";

/// The shared library inside a MuJoCo folder, trying the layouts of a wheel, an install and a
/// build tree, the versioned name first.
pub(crate) fn library_in(dir: &Path) -> Option<PathBuf> {
    let names = [
        format!("libmujoco.so.{MUJOCO_VERSION}"),
        "libmujoco.so".to_owned(),
    ];
    ["lib", "lib64", "."]
        .iter()
        .flat_map(|sub| names.iter().map(move |name| dir.join(sub).join(name)))
        .find(|candidate| candidate.is_file())
}
