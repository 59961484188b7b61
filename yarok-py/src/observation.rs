//! An observation as Python sees it: a dict of numpy arrays keyed by the dataset's features.

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::worker::{Observed, WorldInfo};

/// `{"observation.state": float32[n], "observation.environment_state": float32[m],
/// "observation.images.…": uint8[h, w, 3]}`; the images' pixels are moved into numpy, not
/// copied.
pub(crate) fn to_dict<'py>(
    py: Python<'py>,
    info: &WorldInfo,
    observed: Observed,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let observation = observed.observation;
    let floats = |values: &[f64]| {
        let values: Vec<f32> = values.iter().map(|v| *v as f32).collect();
        PyArray1::from_vec(py, values)
    };
    dict.set_item("observation.state", floats(&observation.state))?;
    dict.set_item(
        "observation.environment_state",
        floats(&observation.environment_state),
    )?;
    for ((key, [width, height]), pixels) in info.images.iter().zip(observation.images) {
        let image =
            PyArray1::from_vec(py, pixels).reshape([*height as usize, *width as usize, 3])?;
        dict.set_item(key, image)?;
    }
    Ok(dict)
}
