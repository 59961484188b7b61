//! The `yarok` command line, run as a user runs it.

use std::process::Command;

/// What `yarok ARGS` did: its exit status, standard output and standard error.
pub(crate) fn yarok(args: &[&str]) -> (i32, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(args)
        .output()
        .unwrap();
    let text = |bytes: Vec<u8>| String::from_utf8(bytes).unwrap();
    (
        output.status.code().unwrap(),
        text(output.stdout),
        text(output.stderr),
    )
}

/// Runs `yarok ARGS`, asserts that it exits with `code` and that its standard error names every
/// one of `parts` (the place and the nearest name); returns the standard error.
#[track_caller]
pub(crate) fn yarok_fails(args: &[&str], code: i32, parts: &[&str]) -> String {
    let (exited, _, stderr) = yarok(args);
    assert_eq!(
        exited, code,
        "yarok {args:?} exited with {exited}: {stderr}"
    );
    yarok_test::assert_says(stderr, parts)
}

/// The arguments of `yarok tactile calibrate UNTOUCHED PRESSES OUT --sensor digit` with one
/// candidate geometry (contact scale 0.7, spread 6 px): a fit in a fraction of a second.
pub(crate) fn quick_calibrate(untouched: &str, presses: &str, out: &str) -> Vec<String> {
    [
        "tactile",
        "calibrate",
        untouched,
        presses,
        out,
        "--sensor",
        "digit",
        "--contact-scale",
        "0.7",
        "--spread",
        "6",
    ]
    .map(str::to_owned)
    .to_vec()
}
