//! The command line writes to standard output that may close or fail under it: a reader that
//! goes away (`yarok compose … | head -c 1`, `yarok run … | true`) ends the output quietly, as Unix
//! tools do, and a full disk (`> /dev/full`) is an error that says so; neither panics.

use std::io::Read;
use std::process::{Command, Stdio};

/// Runs `yarok ARGS` with its standard output a pipe read for `keep` bytes and then closed:
/// the exit status and standard error.
fn with_a_reader_that_leaves(args: &[&str], keep: usize) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = child.stdout.take().unwrap();
    let mut kept = vec![0; keep];
    stdout.read_exact(&mut kept).unwrap();
    drop(stdout);
    let output = child.wait_with_output().unwrap();
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn a_reader_that_goes_away_ends_the_output_quietly() {
    for (args, keep) in [
        (&["compose", "pick_and_place_world"][..], 1),
        (&["run", "--list"][..], 1),
        (&["--help"][..], 1),
        // Its behaviour logs lines after the reader left; the run goes on to its end.
        (&["run", "pick_and_place_world"][..], 0),
    ] {
        let (code, stderr) = with_a_reader_that_leaves(args, keep);
        assert_eq!(code, Some(0), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}

#[test]
fn a_full_standard_output_is_an_error_that_says_so() {
    let output = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(["compose", "pick_and_place_world"])
        .stdout(std::fs::File::create("/dev/full").unwrap())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("cannot write to standard output") && !stderr.contains("panicked"),
        "{stderr}"
    );
}
