//! A `yarok` binary copied to another machine runs with the MuJoCo folder copied beside it
//! (`mujoco/lib/libmujoco.so.4.0.1`), which it opens before the library found when it was built.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `yarok` binary copied into a folder of its own, with `library` as the MuJoCo beside it.
fn copied_with(library: &[u8]) -> tempfile::TempDir {
    let folder = tempfile::tempdir().unwrap();
    std::fs::copy(env!("CARGO_BIN_EXE_yarok"), folder.path().join("yarok")).unwrap();
    let lib = folder
        .path()
        .join(yarok::mjc::BESIDE_EXECUTABLE)
        .join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::write(lib.join("libmujoco.so.4.0.1"), library).unwrap();
    folder
}

fn run_empty_world(folder: &Path) -> Output {
    Command::new(folder.join("yarok"))
        .args(["run", "empty_world", "--set", "behaviour/seconds=0.1"])
        .env_remove("MUJOCO_DIR")
        .output()
        .unwrap()
}

/// The library this test process opened, as the dynamic loader mapped it.
fn loaded_mujoco() -> PathBuf {
    yarok::mjc::mujoco_version().unwrap();
    let maps = std::fs::read_to_string("/proc/self/maps").unwrap();
    let line = maps
        .lines()
        .find(|line| line.contains("libmujoco"))
        .unwrap();
    PathBuf::from(line.split_whitespace().last().unwrap())
}

#[test]
fn a_copied_binary_opens_the_mujoco_copied_beside_it() {
    // Not a library: the binary says so naming the file beside it, so that is where it looked.
    let bogus = copied_with(b"not a library");
    let output = run_empty_world(bogus.path());
    let stderr = String::from_utf8_lossy(&output.stderr);
    let beside = bogus.path().join("mujoco/lib/libmujoco.so.4.0.1");
    assert!(!output.status.success(), "{stderr}");
    assert!(
        stderr.contains(&format!("cannot open MuJoCo at {}", beside.display())),
        "{stderr}"
    );
    // MuJoCo itself beside it: the run goes through.
    let real = copied_with(&std::fs::read(loaded_mujoco()).unwrap());
    let output = run_empty_world(real.path());
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}
