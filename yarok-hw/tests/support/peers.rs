//! The third-party test peers `scripts/setup-test-peers.sh` installs: their Python, and the
//! project's scripts that drive them.

use std::path::PathBuf;

/// The Python of the peers' virtual environment (`${YAROK_CACHE_DIR:-~/.cache/yarok}/peers`).
pub(crate) fn python() -> PathBuf {
    let python = std::env::var_os("YAROK_CACHE_DIR")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cache/yarok")))
        .expect("YAROK_CACHE_DIR or HOME")
        .join("peers/bin/python");
    assert!(
        python.exists(),
        "{} is missing: run `bash scripts/setup-test-peers.sh` (scripts/test.sh does)",
        python.display()
    );
    python
}

/// `scripts/peers/{name}`, found above whichever crate's tests run.
pub(crate) fn script(name: &str) -> PathBuf {
    let script = format!("scripts/peers/{name}");
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .map(|folder| folder.join(&script))
        .find(|path| path.is_file())
        .unwrap_or_else(|| panic!("{script} not found above {}", env!("CARGO_MANIFEST_DIR")))
}
