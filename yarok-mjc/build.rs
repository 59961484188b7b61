//! Finds MuJoCo (fetching it from PyPI into a per-user cache on first use) and tells the crate
//! where its shared library is. The library is opened at run time, so no link flags or rpath are
//! needed and every binary that depends on yarok-mjc, downstream crates' included, finds it.

#[path = "src/locate.rs"]
#[allow(dead_code, unreachable_pub)]
mod locate;

use std::path::{Path, PathBuf};
use std::process::{Command, exit};

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=scripts/fetch_mujoco.py");
    for var in [
        locate::MUJOCO_DIR_VAR,
        "YAROK_CACHE_DIR",
        "XDG_CACHE_HOME",
        "HOME",
    ] {
        println!("cargo::rerun-if-env-changed={var}");
    }
    let library = match std::env::var_os(locate::MUJOCO_DIR_VAR) {
        Some(dir) => user_library(Path::new(&dir)),
        None => cached_library(),
    };
    println!("cargo::rerun-if-changed={}", library.display());
    println!(
        "cargo::rustc-env=YAROK_MUJOCO_LIBRARY={}",
        library.display()
    );
}

fn user_library(dir: &Path) -> PathBuf {
    locate::library_in(dir).unwrap_or_else(|| {
        stop(&format!(
            "{}={} holds no lib/libmujoco.so.{} (nor lib/libmujoco.so); point it at a MuJoCo {} \
             folder, or unset it to let yarok fetch MuJoCo from PyPI",
            locate::MUJOCO_DIR_VAR,
            dir.display(),
            locate::MUJOCO_VERSION,
            locate::MUJOCO_VERSION
        ))
    })
}

fn cache_root() -> PathBuf {
    let env_dir = |var: &str| {
        std::env::var_os(var)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    env_dir("YAROK_CACHE_DIR")
        .or_else(|| env_dir("XDG_CACHE_HOME").map(|d| d.join("yarok")))
        .or_else(|| env_dir("HOME").map(|d| d.join(".cache").join("yarok")))
        .unwrap_or_else(|| {
            stop("no cache folder for MuJoCo: set YAROK_CACHE_DIR (or HOME), or set MUJOCO_DIR")
        })
}

fn cached_library() -> PathBuf {
    let dir = cache_root().join(format!("mujoco-{}", locate::MUJOCO_VERSION));
    if let Some(library) = locate::library_in(&dir) {
        return library;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/fetch_mujoco.py");
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".to_owned());
    match Command::new(&python).arg(&script).arg(&dir).status() {
        Ok(status) if status.success() => {}
        Ok(_) => stop("fetching MuJoCo failed; the lines above say why and what to do"),
        Err(error) => stop(&format!(
            "could not start `{python}` to fetch MuJoCo ({error}); install python3 with pip, \
             or set MUJOCO_DIR to a MuJoCo {} folder",
            locate::MUJOCO_VERSION
        )),
    }
    locate::library_in(&dir).unwrap_or_else(|| stop("MuJoCo fetch finished but left no library"))
}

fn stop(message: &str) -> ! {
    eprintln!("error: {message}");
    exit(1)
}
