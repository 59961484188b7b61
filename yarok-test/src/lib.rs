//! Test doubles for yarok's tests, as tokio-test is to tokio: a dev-dependency of the workspace's
//! crates, never of a user's build.
//!
//! - [`ur_controller`]: a fake UR controller (RTDE, dashboard, secondary and real-time
//!   interfaces, and a Robotiq gripper socket) on a loopback address of its own;
//! - [`scripted_printer`]: a Marlin printer that expects the driver's lines byte for byte;
//! - [`virtual_printer`]: OctoPrint's VirtualPrinter, a third-party Marlin, on a pseudo-terminal;
//! - [`peers`]: the third-party programs `scripts/setup-test-peers.sh` installs;
//! - [`generator`]: a deterministic generator of inputs for the parsers' tests;
//! - [`XServer`]: an Xvfb of a test's own, for the viewer's tests and benchmarks;
//! - [`assert_says`]: an error's text checked for what it must name;
//! - [`assert_succeeded`]: a program's run checked for success, showing what it wrote if not.

pub mod generator;
pub mod peers;
pub mod scripted_printer;
pub mod ur_controller;
pub mod virtual_printer;
mod x_server;

pub use x_server::XServer;

/// Asserts that `error`'s text names every one of `parts` (a component path, a device, a key),
/// printing the text and what it lacks when it does not; returns the text for further checks.
///
/// # Examples
///
/// ```
/// let error = "/arm: the controller is in local control: switch it to remote";
/// yarok_test::assert_says(error, &["/arm", "local control", "remote"]);
/// ```
#[track_caller]
pub fn assert_says(error: impl std::fmt::Display, parts: &[&str]) -> String {
    let text = error.to_string();
    let missing: Vec<&str> = parts
        .iter()
        .copied()
        .filter(|part| !text.contains(part))
        .collect();
    assert!(missing.is_empty(), "{text}\n  does not say: {missing:?}");
    text
}

/// Asserts that the program whose run is `output` exited successfully, printing its standard
/// output and error when it did not.
#[track_caller]
pub fn assert_succeeded(output: &std::process::Output) {
    assert!(
        output.status.success(),
        "{}\n{}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}
