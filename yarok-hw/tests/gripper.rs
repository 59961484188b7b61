//! The Robotiq gripper client against the fake controller's URCap socket: activation, a grasp
//! that stops on an object (taking the time the fingers need), opening to the position, a
//! fault mid-motion and a move before activation as errors naming the gripper; scripted
//! sockets (an odd reply, silence, a closed line) as errors; and the fake's socket driven by
//! pyrobotiqur (a third-party client, run as a separate process), which grasps the same way.

use std::time::{Duration, Instant};

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use yarok_hw::robotiq::{Gripper, GripperError, Motion};

use yarok_test::peers;
use yarok_test::ur_controller;

use ur_controller::{FakeController, GRIPPER_PORT, Profile};

async fn connect(fake: &FakeController) -> Gripper<TcpStream> {
    let stream = TcpStream::connect((fake.host.as_str(), GRIPPER_PORT))
        .await
        .unwrap();
    Gripper::new(stream, fake.host.clone(), Duration::from_secs(1))
}

#[tokio::test]
async fn activation_a_grasp_on_an_object_and_opening() {
    let fake = FakeController::start(Profile::ESeries);
    let mut gripper = connect(&fake).await;
    gripper.activate(Duration::from_secs(3)).await.unwrap();
    assert_eq!(fake.fingers().sta, 3);

    fake.place_object(Some(120));
    let started = Instant::now();
    gripper.go_to(255, 255, 100).await.unwrap();
    let grasp = gripper.finish_motion(Duration::from_secs(3)).await.unwrap();
    assert_eq!(grasp.motion, Motion::ObjectWhileClosing);
    assert_eq!((grasp.position, grasp.requested), (120, 255));
    // 120 of 255 at full speed (a 0.4 s stroke): about 0.19 s.
    assert!(
        started.elapsed() >= Duration::from_millis(150),
        "{:?}",
        started.elapsed()
    );
    assert_eq!(fake.fingers().force, 100);

    gripper.go_to(0, 255, 0).await.unwrap();
    let open = gripper.finish_motion(Duration::from_secs(3)).await.unwrap();
    assert_eq!((open.motion, open.position), (Motion::AtPosition, 0));
}

#[tokio::test]
async fn faults_are_errors_naming_the_gripper() {
    let fake = FakeController::start(Profile::Cb3);
    let mut gripper = connect(&fake).await;
    gripper.go_to(255, 0, 50).await.unwrap();
    let early = gripper
        .finish_motion(Duration::from_secs(1))
        .await
        .unwrap_err();
    assert!(
        matches!(early, GripperError::Fault { code: 5, .. }),
        "{early}"
    );

    gripper.activate(Duration::from_secs(3)).await.unwrap();
    gripper.go_to(255, 0, 50).await.unwrap();
    tokio::time::sleep(Duration::from_millis(100)).await;
    fake.gripper_fault(14);
    let fault = gripper
        .finish_motion(Duration::from_secs(3))
        .await
        .unwrap_err();
    assert!(
        matches!(fault, GripperError::Fault { code: 14, .. }),
        "{fault}"
    );
    let message = fault.to_string();
    assert!(
        message.contains(&fake.host) && message.contains("overcurrent"),
        "{message}"
    );
    assert!(fake.fingers().position() < 255, "the fingers stopped");

    fake.place_object(None);
    let slow = gripper
        .activate(Duration::from_millis(50))
        .await
        .unwrap_err();
    assert!(matches!(slow, GripperError::Timeout { .. }), "{slow}");
}

/// A socket that answers the first command with `reply` (if any), then closes or stays silent.
async fn scripted(reply: Option<&'static str>, close: bool) -> GripperError {
    let (ours, mut theirs) = tokio::io::duplex(1024);
    tokio::spawn(async move {
        let mut command = [0u8; 8];
        theirs.read_exact(&mut command).await.unwrap();
        assert_eq!(&command, b"GET POS\n");
        if let Some(reply) = reply {
            theirs.write_all(reply.as_bytes()).await.unwrap();
        }
        if !close {
            std::future::pending::<()>().await;
        }
    });
    let mut gripper = Gripper::new(ours, "gripper-test", Duration::from_secs(1));
    gripper.get("POS").await.unwrap_err()
}

#[tokio::test(start_paused = true)]
async fn odd_replies_silence_and_a_closed_line_are_errors() {
    let odd = scripted(Some("POS abc\n"), false).await;
    assert!(matches!(odd, GripperError::Unexpected { .. }), "{odd}");
    let silent = scripted(None, false).await;
    assert!(matches!(silent, GripperError::Timeout { .. }), "{silent}");
    let closed = scripted(None, true).await;
    assert!(matches!(closed, GripperError::Closed { .. }), "{closed}");
    for error in [odd, silent, closed] {
        assert!(error.to_string().contains("gripper-test"), "{error}");
    }
}

#[test]
fn pyrobotiqur_grasps_with_the_fake_gripper() {
    let fake = FakeController::start(Profile::ESeries);
    fake.place_object(Some(140));
    let stdout = peers::run("pyrobotiqur_grasp.py", &[&fake.host]);
    let step = |name: &str| peers::field(&stdout, name);
    assert_eq!(step("status"), "3", "{stdout}");
    assert_eq!(
        step("closed"),
        "140 2",
        "stopped on the object while closing: {stdout}"
    );
    assert_eq!(step("opened"), "0 3", "at the position: {stdout}");
    assert_eq!(step("fault"), "0", "{stdout}");
    let commands = fake.fingers().commands;
    assert!(commands.iter().any(|c| c == "SET GTO 1"), "{commands:?}");
}
