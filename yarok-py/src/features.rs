//! [`Features`]: what a world's observations and actions hold, as Python reads it.

use pyo3::prelude::*;

use crate::worker::WorldInfo;

/// A world's features: the names in `observation.state`, `observation.environment_state` and
/// `action`, the image keys and shapes, the action's ranges, and the tick's length.
#[pyclass(module = "yarok._native", frozen)]
pub(crate) struct Features(pub(crate) WorldInfo);

#[pymethods]
impl Features {
    /// `observation.state`'s names: the joints.
    #[getter]
    fn state_names(&self) -> Vec<String> {
        self.0.state_names.clone()
    }

    /// `observation.environment_state`'s names: each free body's `x`, `y`, `z`, `qw` … `qz`.
    #[getter]
    fn environment_names(&self) -> Vec<String> {
        self.0.environment_names.clone()
    }

    /// The image features: `{key: (height, width, 3)}`.
    #[getter]
    fn images(&self) -> Vec<(String, (u32, u32, u32))> {
        self.0
            .images
            .iter()
            .map(|(key, [width, height])| (key.clone(), (*height, *width, 3)))
            .collect()
    }

    /// `action`'s names.
    #[getter]
    fn action_names(&self) -> Vec<String> {
        self.0.action_names.clone()
    }

    /// Each action number's range, `(lowest, highest)`.
    #[getter]
    fn action_ranges(&self) -> Vec<(f64, f64)> {
        self.0
            .action_ranges
            .iter()
            .map(|[lowest, highest]| (*lowest, *highest))
            .collect()
    }

    /// Seconds of platform time a tick.
    #[getter]
    fn timestep(&self) -> f64 {
        self.0.timestep
    }
}
