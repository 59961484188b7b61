//! The Zenoh bridge (feature `zenoh`) on loopback, talked to by the Zenoh project's own Python
//! client (eclipse-zenoh, a separate process): it reads a DigitWorld's joint states, its arm's
//! state and a DIGIT's image, commands the arm to joints and sees it arrive, has gripper
//! positions outside 0–255 and a command of a megabyte refused with a reply; a stop command ends
//! the run cleanly. A second world on the same keys is refused.
#![cfg(feature = "zenoh")]

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use yarok_test::peers;

#[test]
fn a_third_party_client_reads_the_world_and_moves_the_arm() {
    let port = 20000 + std::process::id() % 20000;
    let endpoint = format!("tcp/127.0.0.1:{port}");
    let mut world = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(["run", "digit_world", "--behaviour", "idle", "--bridge"])
        .args([
            "--set",
            "behaviour/seconds=120",
            "--set",
            "platform/realtime=true",
        ])
        .args(["--set", &format!("plugins/zenoh/listen=[{endpoint:?}]")])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The bridge listens once the world has started.
    let started = Instant::now();
    while std::net::TcpStream::connect(("127.0.0.1", port as u16)).is_err() {
        if started.elapsed() > Duration::from_secs(60) || world.try_wait().unwrap().is_some() {
            let _ = world.kill();
            let output = world.wait_with_output().unwrap();
            panic!("no bridge: {}", String::from_utf8_lossy(&output.stderr));
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let target = [0.3, -1.7, 1.8, -1.6, -1.57, 0.0];
    let output = Command::new(peers::python())
        .arg(peers::script("zenoh_client.py"))
        .args([&endpoint, "world", &format!("{target:?}")])
        .output()
        .unwrap();
    let printed = String::from_utf8_lossy(&output.stdout).into_owned();
    if !output.status.success() {
        let _ = world.kill();
        panic!("{printed}\n{}", String::from_utf8_lossy(&output.stderr));
    }
    let numbers = |name: &str| -> Vec<f64> {
        peers::field(&printed, name)
            .split(' ')
            .filter_map(|v| v.parse().ok())
            .collect()
    };
    assert!(numbers("joint_states")[0] >= 5.0, "{printed}");
    assert!(
        peers::field(&printed, "joint_states").contains("arm/shoulder_pan"),
        "{printed}"
    );
    // The world's start pose, as the bridge published it.
    let start = numbers("arm_q");
    let expected = yarok::components::worlds::DIGIT_WORLD_START;
    assert!(
        start
            .iter()
            .zip(expected)
            .all(|(a, b)| (a - b).abs() < 1e-3),
        "{start:?}"
    );
    let image: Vec<&str> = peers::field(&printed, "image").split(' ').collect();
    assert!(
        image[0].ends_with("_digit/image") && image[1..] == ["240", "320"],
        "{image:?}"
    );
    assert_eq!(peers::field(&printed, "reply"), r#"{"ok": true}"#);
    let reached = numbers("reached");
    assert!(
        reached[1..]
            .iter()
            .zip(target)
            .all(|(a, b)| (a - b).abs() < 0.01),
        "{reached:?}"
    );
    // A gripper position outside its register is refused, not obeyed.
    for position in ["256", "-1", "1.5"] {
        let reply = peers::field(&printed, &format!("gripper_reply_{position}"));
        assert!(
            reply.contains(r#""ok": false"#)
                && reply.contains(&format!(
                    "move_to {position} is not a whole number from 0 to 255"
                )),
            "{reply}"
        );
    }
    // A command of a megabyte is answered, refused unread.
    let huge = peers::field(&printed, "huge_reply");
    assert!(
        huge.contains(r#""ok": false"#)
            && huge.contains("bytes, more than the 65536 a command may be"),
        "{huge}"
    );
    // The client's stop command ends the run.
    let started = Instant::now();
    let status = loop {
        if let Some(status) = world.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > Duration::from_secs(10) {
            let _ = world.kill();
            panic!("the world did not stop");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(status.success(), "{status}");
}

#[test]
fn a_world_name_that_would_match_other_worlds_keys_is_refused() {
    for world in ["a/*/b", "**", "lab//arm", "", "what?", "x$y"] {
        let output = Command::new(env!("CARGO_BIN_EXE_yarok"))
            .args(["run", "empty_world", "--bridge", "--set"])
            .arg(format!("plugins/zenoh/world={world:?}"))
            .output()
            .unwrap();
        assert!(!output.status.success(), "{world:?} was accepted");
        yarok_test::assert_says(
            String::from_utf8_lossy(&output.stderr),
            &[&format!("`world` {world:?} is no plain key")],
        );
    }
}

/// A second world bridging the same keys on the same Zenoh network is refused when it starts,
/// naming the keys (the first keeps them).
#[test]
fn a_second_world_on_the_same_keys_is_refused() {
    let port = 20000 + (std::process::id() + 7) % 20000;
    let world = |extra: &[String]| {
        Command::new(env!("CARGO_BIN_EXE_yarok"))
            .args(["run", "printer_world", "--behaviour", "idle", "--bridge"])
            .args([
                "--set",
                "behaviour/seconds=60",
                "--set",
                "platform/realtime=true",
            ])
            .args(extra)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let mut first = world(&[
        "--set".to_owned(),
        format!("plugins/zenoh/listen=[\"tcp/127.0.0.1:{port}\"]"),
    ]);
    let started = Instant::now();
    while std::net::TcpStream::connect(("127.0.0.1", port as u16)).is_err() {
        if started.elapsed() > Duration::from_secs(60) || first.try_wait().unwrap().is_some() {
            let _ = first.kill();
            let output = first.wait_with_output().unwrap();
            panic!("no bridge: {}", String::from_utf8_lossy(&output.stderr));
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let second = world(&[
        "--set".to_owned(),
        format!("plugins/zenoh/listen=[\"tcp/127.0.0.1:{}\"]", port + 1),
        "--set".to_owned(),
        format!("plugins/zenoh/connect=[\"tcp/127.0.0.1:{port}\"]"),
    ])
    .wait_with_output()
    .unwrap();
    let _ = first.kill();
    let _ = first.wait();
    let stderr = String::from_utf8_lossy(&second.stderr);
    assert!(!second.status.success(), "{stderr}");
    assert!(
        stderr.contains("another world already bridges yarok/world"),
        "{stderr}"
    );
}
