//! The tactile golden data the tests read (`tests/golden/tactile` at the workspace root).

use std::path::PathBuf;

use yarok_components::tactile::npy;

/// A file or folder of the golden data.
pub(crate) fn golden(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/golden/tactile")
        .join(path)
}

/// The background every case of `model` was rendered over, RGB.
pub(crate) fn background(model: &str) -> Vec<u8> {
    image::open(golden(&format!("{model}/background.png")))
        .unwrap()
        .to_rgb8()
        .into_raw()
}

/// The input depth map of a golden case.
pub(crate) fn depth(model: &str, case: &str) -> npy::NpyArray {
    npy::read(golden(&format!("{model}/{case}/input_depth.npy.gz"))).unwrap()
}
