//! A world MuJoCo takes long to compile (its compile time grows faster than the world's size:
//! about 17 s for 20 000 bodies) is not a silent process: after two seconds a warning says what
//! is being compiled and why it may take long, and an interrupt (Ctrl-C) ends the process
//! there and then. Checked from a child process, since both are process-wide.

use std::io::{BufRead, BufReader};
use std::os::unix::process::ExitStatusExt;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use yarok::core::config::RunConfig;
use yarok::prelude::*;
use yarok_test::assert_says;

const CHILD: &str = "YAROK_LONG_COMPILE_CHILD";

/// Twenty thousand bodies in a row, each on a hinge.
struct Row;

impl Component for Row {
    fn declaration() -> Declaration {
        Declaration::new("row").template(
            r#"<mujoco><worldbody><for each="range(20000)" as="i">
                 <body pos="{i * 0.01} 0 0"><joint/><geom size="0.004"/></body>
               </for></worldbody></mujoco>"#,
        )
    }
}

/// The child: builds the world, with no model cache so that it compiles every time.
#[test]
fn compiling_child() {
    if std::env::var(CHILD).is_err() {
        return;
    }
    let mut config = RunConfig::default();
    config.set("platform/model_cache=false").unwrap();
    let built = yarok::platform().world::<Row>().config(config).build();
    println!("built: {}", built.is_ok());
}

#[test]
fn a_long_compile_says_so_and_an_interrupt_ends_it() {
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "compiling_child",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, "1")
        .env_remove("RUST_LOG")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut notice = String::new();
    while !notice.contains("MuJoCo is compiling") {
        notice.clear();
        assert!(
            stderr.read_line(&mut notice).unwrap() > 0,
            "the child ended without a notice"
        );
    }
    let noticed = started.elapsed();
    assert_says(&notice, &["20000 bodies", "can take minutes"]);
    let interrupted = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(interrupted.success());
    let signalled = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        assert!(
            signalled.elapsed() < Duration::from_secs(2),
            "the interrupt did not end the compile"
        );
        std::thread::sleep(Duration::from_millis(10));
    };
    assert_eq!(status.signal(), Some(2), "{status:?}");
    println!(
        "notice after {noticed:?}, exit {:?} after the interrupt",
        signalled.elapsed()
    );
}
