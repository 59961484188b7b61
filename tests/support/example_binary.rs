//! The examples' binaries, for tests that run them as a user does.

use std::path::PathBuf;
use std::process::Command;

/// The example `name`'s binary beside this test, built now if its code changed (a run of one
/// test target, `--test NAME`, builds no examples: a test must never run a stale one).
pub(crate) fn example_binary(name: &str) -> PathBuf {
    let deps = std::env::current_exe().unwrap();
    let profile = deps.parent().and_then(|d| d.parent()).unwrap();
    let mut build = Command::new(env!("CARGO"));
    build.args(["build", "--quiet", "--example", name]);
    if profile.file_name().is_some_and(|p| p == "release") {
        build.arg("--release");
    }
    let status = build.status().unwrap();
    assert!(status.success(), "cargo build --example {name}: {status}");
    profile.join("examples").join(name)
}
