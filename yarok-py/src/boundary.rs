//! What a call from Python meets: yarok's refusals and failures as `YarokError`, Ctrl-C heard
//! while a world works without the GIL, and one thread at a time per world.

use std::sync::{Mutex, MutexGuard, OnceLock, TryLockError};

use pyo3::prelude::*;
use pyo3::types::PyType;

pyo3::create_exception!(
    _native,
    YarokError,
    pyo3::exceptions::PyRuntimeError,
    "What yarok refused or what failed in a world, in yarok's words."
);

/// Whether Ctrl-C (or another signal Python handles) arrived: checked with the GIL, while a
/// world works without it. The exception is kept to be raised.
pub(crate) fn interrupted(pending: &mut Option<PyErr>) -> impl FnMut() -> bool + '_ {
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
pub(crate) fn exclusive<'a, T>(lock: &'a Mutex<T>, what: &str) -> PyResult<MutexGuard<'a, T>> {
    lock.try_lock().map_err(|failure| match failure {
        TryLockError::WouldBlock => error(format!(
            "{what} is busy with a call from another thread: step a world from one thread at a \
             time (give each thread a world of its own, or use yarok.Worlds)"
        )),
        TryLockError::Poisoned(_) => error(format!("{what} was left broken by an earlier failure")),
    })
}

/// The exception yarok's errors are raised as when it is not this module's own `YarokError`:
/// an extension module of another crate raises the `yarok` package's, so that one `except`
/// catches both.
static RAISED_AS: OnceLock<Py<PyType>> = OnceLock::new();

/// Raises yarok's errors as `exception` from now on.
pub(crate) fn raise_as(exception: &Bound<'_, PyType>) {
    let _ = RAISED_AS.set(exception.clone().unbind());
}

/// yarok's error text as a Python exception.
pub(crate) fn error(text: String) -> PyErr {
    match RAISED_AS.get() {
        Some(exception) => Python::attach(|py| PyErr::from_type(exception.bind(py).clone(), text)),
        None => YarokError::new_err(text),
    }
}
