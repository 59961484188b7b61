//! The examples' binaries, for tests that run them as a user does.

use std::path::PathBuf;
use std::process::Command;

/// The example `name`'s binary, built beside this test, or built now.
pub(crate) fn example_binary(name: &str) -> PathBuf {
    let deps = std::env::current_exe().unwrap();
    let profile = deps.parent().and_then(|d| d.parent()).unwrap();
    let example = profile.join("examples").join(name);
    if !example.is_file() {
        let status = Command::new(env!("CARGO"))
            .args(["build", "--example", name])
            .status()
            .unwrap();
        assert!(status.success());
    }
    example
}
