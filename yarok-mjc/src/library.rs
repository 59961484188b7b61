//! Opening libmujoco once per process, checking its version and routing its log to `tracing`.

use std::ffi::CStr;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::error::LibraryError;
use crate::locate;
use crate::sys;

/// The path `build.rs` found (or fetched) MuJoCo at.
const BUILT_WITH: &str = env!("YAROK_MUJOCO_LIBRARY");

static MUJOCO: OnceLock<Result<sys::MuJoCo, LibraryError>> = OnceLock::new();

/// The MuJoCo folder a program ships with it, set by [`use_bundled_mujoco`].
static BUNDLED: OnceLock<PathBuf> = OnceLock::new();

/// The folder beside the executable a copied `yarok` binary finds its MuJoCo in.
pub const BESIDE_EXECUTABLE: &str = "mujoco";

/// The loaded MuJoCo library, opened on first use, from the first of: the folder `MUJOCO_DIR`
/// names; the folder the program bundles ([`use_bundled_mujoco`]); a [`BESIDE_EXECUTABLE`]
/// folder beside the executable; the library found when yarok was built.
pub(crate) fn mujoco() -> Result<&'static sys::MuJoCo, LibraryError> {
    MUJOCO.get_or_init(load).as_ref().map_err(Clone::clone)
}

/// The version of the loaded library as MuJoCo reports it, e.g. `"4.0.1"`.
///
/// # Errors
///
/// Fails when libmujoco cannot be found or opened, or is not the version yarok's bindings were
/// generated from.
///
/// # Examples
///
/// ```
/// assert_eq!(yarok_mjc::mujoco_version()?, "4.0.1");
/// # Ok::<(), yarok_mjc::LibraryError>(())
/// ```
pub fn mujoco_version() -> Result<String, LibraryError> {
    let mj = mujoco()?;
    // SAFETY: mj_versionString returns a pointer to a static NUL-terminated string.
    let version = unsafe { CStr::from_ptr(mj.mj_versionString()) };
    Ok(version.to_string_lossy().into_owned())
}

/// Makes `dir` (a MuJoCo folder: `lib/libmujoco.so.4.0.1`) where MuJoCo is found when
/// `MUJOCO_DIR` is not set: for programs that ship MuJoCo with them, as yarok's Python wheel
/// does, so that they run on machines where yarok was never built. Returns whether it takes
/// effect: not once MuJoCo has been opened, nor when a folder was bundled before.
///
/// # Examples
///
/// ```
/// // MuJoCo is open already here (or MUJOCO_DIR is set): a later folder changes nothing.
/// yarok_mjc::mujoco_version()?;
/// assert!(!yarok_mjc::use_bundled_mujoco("/opt/elsewhere/mujoco"));
/// # Ok::<(), yarok_mjc::LibraryError>(())
/// ```
pub fn use_bundled_mujoco(dir: impl Into<PathBuf>) -> bool {
    MUJOCO.get().is_none() && BUNDLED.set(dir.into()).is_ok()
}

fn library_path() -> Result<PathBuf, LibraryError> {
    if let Some(dir) = std::env::var_os(locate::MUJOCO_DIR_VAR) {
        return locate::library_in(Path::new(&dir)).ok_or_else(|| LibraryError::NotInMujocoDir {
            dir: PathBuf::from(dir),
        });
    }
    if let Some(dir) = BUNDLED.get() {
        return locate::library_in(dir)
            .ok_or_else(|| LibraryError::NotInBundledDir { dir: dir.clone() });
    }
    let beside = std::env::current_exe()
        .ok()
        .and_then(|exe| Some(exe.parent()?.join(BESIDE_EXECUTABLE)))
        .and_then(|dir| locate::library_in(&dir));
    Ok(beside.unwrap_or_else(|| PathBuf::from(BUILT_WITH)))
}

fn load() -> Result<sys::MuJoCo, LibraryError> {
    let path = library_path()?;
    // SAFETY: opening libmujoco runs only its static initialisers, which have no preconditions.
    let library =
        unsafe { libloading::Library::new(&path) }.map_err(|source| LibraryError::Open {
            path: path.clone(),
            reason: source.to_string(),
        })?;
    // SAFETY: the symbol types in `sys` were generated from the headers of the version checked
    // just below; a library missing a symbol is rejected by `from_library`.
    let mj =
        unsafe { sys::MuJoCo::from_library(library) }.map_err(|source| LibraryError::Open {
            path: path.clone(),
            reason: source.to_string(),
        })?;
    // SAFETY: mj_version has no preconditions.
    let version = unsafe { mj.mj_version() };
    if i64::from(version) != i64::from(sys::mjVERSION_HEADER) {
        return Err(LibraryError::VersionMismatch {
            path,
            library: version,
            header: sys::mjVERSION_HEADER,
        });
    }
    // SAFETY: log_to_tracing matches mjfLogHandler, is thread-safe and never calls mju_error.
    unsafe { mj.mju_setLogHandler(Some(log_to_tracing)) };
    tracing::debug!(path = %path.display(), version, "loaded MuJoCo");
    Ok(mj)
}

/// MuJoCo's log handler: warnings and information go to `tracing`; an error is fatal.
///
/// MuJoCo assumes an error handler never returns, and a Rust panic must not unwind into C, so a
/// MuJoCo error (which the safe layer's checks are there to prevent) is logged, then aborts.
/// Compile errors do not come here: `mj_loadXML` reports them through its error buffer.
unsafe extern "C" fn log_to_tracing(message: *const sys::mjLogMessage) {
    // SAFETY: MuJoCo passes a valid message whose subject is a NUL-terminated array.
    let message = unsafe { &*message };
    // SAFETY: `subject` is a fixed array that MuJoCo NUL-terminates.
    let subject = unsafe { CStr::from_ptr(message.subject.as_ptr()) }.to_string_lossy();
    match u32::try_from(message.level).unwrap_or(sys::mjLOG_ERROR) {
        sys::mjLOG_ERROR => {
            tracing::error!(target: "mujoco", "{subject}");
            eprintln!("MuJoCo error (fatal): {subject}");
            std::process::abort();
        }
        sys::mjLOG_WARNING => tracing::warn!(target: "mujoco", "{subject}"),
        sys::mjLOG_INFO => tracing::info!(target: "mujoco", "{subject}"),
        _ => tracing::debug!(target: "mujoco", "{subject}"),
    }
}
