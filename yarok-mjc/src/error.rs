//! Errors of the MuJoCo layer, one enum per subsystem.

use std::path::PathBuf;

use crate::ObjectKind;

/// libmujoco could not be used.
#[derive(Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum LibraryError {
    /// `MUJOCO_DIR` is set but holds no MuJoCo shared library.
    #[error(
        "MUJOCO_DIR={} holds no lib/libmujoco.so.{} (nor lib/libmujoco.so)",
        dir.display(),
        crate::locate::MUJOCO_VERSION
    )]
    NotInMujocoDir {
        /// The folder `MUJOCO_DIR` named.
        dir: PathBuf,
    },
    /// The MuJoCo folder the program bundles holds no MuJoCo shared library.
    #[error(
        "the MuJoCo folder this program ships with, {}, holds no lib/libmujoco.so.{}",
        dir.display(),
        crate::locate::MUJOCO_VERSION
    )]
    NotInBundledDir {
        /// The folder [`use_bundled_mujoco`](crate::use_bundled_mujoco) named.
        dir: PathBuf,
    },
    /// The shared library could not be opened or lacks a function yarok needs.
    #[error("cannot open MuJoCo at {}: {reason}", path.display())]
    Open {
        /// The library file.
        path: PathBuf,
        /// What the dynamic loader said.
        reason: String,
    },
    /// The library is another version than the bindings were generated from.
    #[error("MuJoCo at {} is version {library}, yarok needs {header}", path.display())]
    VersionMismatch {
        /// The library file.
        path: PathBuf,
        /// `mj_version()` of the library.
        library: i32,
        /// `mjVERSION_HEADER` of the bindings.
        header: u32,
    },
}

/// A model could not be built or a name could not be resolved in it.
#[derive(Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// libmujoco is unavailable.
    #[error(transparent)]
    Library(#[from] LibraryError),
    /// MuJoCo rejected the MJCF (parse or compile error); `message` is MuJoCo's own.
    #[error("MuJoCo cannot load {origin}: {message}")]
    Compile {
        /// Where the MJCF came from: a file path or `<string>`.
        origin: String,
        /// MuJoCo's error message.
        message: String,
    },
    /// A string handed to MuJoCo contains a NUL byte.
    #[error("{what} contains a NUL byte")]
    InteriorNul {
        /// Which input: the MJCF, an asset name, a path or an object name.
        what: String,
    },
    /// An in-memory asset could not be added to MuJoCo's virtual file system.
    #[error("cannot add asset {name:?} to MuJoCo's virtual file system: {reason}")]
    Asset {
        /// The asset's name.
        name: String,
        /// Why: repeated name, or too large.
        reason: &'static str,
    },
    /// The model has no object of this kind and name.
    #[error("the model has no {kind} named {name:?}")]
    UnknownName {
        /// The kind of object looked up.
        kind: ObjectKind,
        /// The name looked up.
        name: String,
    },
    /// A component's keyframe cannot be placed in the composed model.
    #[error("component {component}: keyframe {name:?}: {reason}")]
    Keyframe {
        /// Path of the component that declared it.
        component: String,
        /// The keyframe's name.
        name: String,
        /// Why.
        reason: String,
    },
    /// MuJoCo could not allocate memory.
    #[error("MuJoCo could not allocate {what}")]
    Allocation {
        /// What was being allocated.
        what: &'static str,
    },
}

yarok_core::debug_as_report!(LibraryError, ModelError);
