//! The dashboard client against the fake controller in both profiles (power, brakes, modes,
//! a protective stop that cannot be unlocked within 5 s and can after, programs), against
//! scripted servers (a wrong welcome, silence, a closed line: errors naming the controller),
//! and the fake's dashboard driven by ur_rtde's DashboardClient (a third-party client, run as a
//! separate process), which accepts every reply.

use std::time::Duration;

use tokio::io::AsyncWriteExt;
use tokio::net::TcpStream;
use yarok_hw::ur::dashboard::{Dashboard, DashboardError, RobotMode, SafetyStatus};

use yarok_test::peers;
use yarok_test::ur_controller;

use ur_controller::{DASHBOARD_PORT, FakeController, Profile};

async fn connect(fake: &FakeController) -> Dashboard<TcpStream> {
    let stream = TcpStream::connect((fake.host.as_str(), DASHBOARD_PORT))
        .await
        .unwrap();
    Dashboard::connect(stream, fake.host.clone(), Duration::from_secs(2))
        .await
        .unwrap()
}

#[tokio::test]
async fn power_brakes_protective_stops_and_programs_in_both_profiles() {
    for profile in [Profile::Cb3, Profile::ESeries] {
        let fake = FakeController::start(profile);
        fake.power_off();
        let mut dashboard = connect(&fake).await;
        let version = dashboard.polyscope_version().await.unwrap();
        assert!(
            version.contains(&profile.version().to_string()),
            "{version}"
        );
        assert_eq!(dashboard.robot_mode().await.unwrap(), RobotMode::PowerOff);
        dashboard.power_on().await.unwrap();
        assert_eq!(dashboard.robot_mode().await.unwrap(), RobotMode::Idle);
        dashboard.brake_release().await.unwrap();
        assert_eq!(dashboard.robot_mode().await.unwrap(), RobotMode::Running);
        assert_eq!(
            dashboard.safety_status().await.unwrap(),
            SafetyStatus::Normal
        );

        fake.protective_stop(Duration::from_secs(1));
        assert_eq!(
            dashboard.safety_status().await.unwrap(),
            SafetyStatus::ProtectiveStop
        );
        let early = dashboard.unlock_protective_stop().await.unwrap_err();
        assert!(
            matches!(&early, DashboardError::Failed { reply, .. } if reply.contains("5s")),
            "{early}"
        );
        assert!(early.to_string().contains(&fake.host), "{early}");
        fake.protective_stop(Duration::from_secs(6));
        dashboard.unlock_protective_stop().await.unwrap();
        assert_eq!(
            dashboard.safety_status().await.unwrap(),
            SafetyStatus::Normal
        );
        dashboard.close_safety_popup().await.unwrap();

        let missing = dashboard.load("pick.txt").await.unwrap_err();
        assert!(missing.to_string().contains("File not found"), "{missing}");
        dashboard.load("/programs/pick.urp").await.unwrap();
        dashboard.play().await.unwrap();
        assert!(fake.arm().playing);
        dashboard.stop().await.unwrap();
        assert!(!fake.arm().playing);
        let invalid = dashboard.command("play\nstop").await.unwrap_err();
        assert!(
            matches!(invalid, DashboardError::Invalid { .. }),
            "{invalid}"
        );
    }
}

#[tokio::test]
async fn remote_control_is_asked_of_an_e_series_controller_only() {
    let e_series = FakeController::start(Profile::ESeries);
    let mut dashboard = connect(&e_series).await;
    assert!(dashboard.is_in_remote_control().await.unwrap());
    e_series.set_remote_control(false);
    assert!(!dashboard.is_in_remote_control().await.unwrap());

    // A CB3 controller has no local mode (and does not understand the question).
    let cb3 = FakeController::start(Profile::Cb3);
    cb3.set_remote_control(false);
    let mut dashboard = connect(&cb3).await;
    assert!(dashboard.is_in_remote_control().await.unwrap());
    let asked = dashboard.command("is in remote control").await.unwrap();
    assert!(asked.starts_with("Could not understand"), "{asked}");
}

/// A dashboard server that sends `welcome` (if any), then closes or stays silent.
async fn scripted(welcome: Option<&'static str>, close: bool) -> DashboardError {
    let (ours, mut theirs) = tokio::io::duplex(1024);
    tokio::spawn(async move {
        if let Some(welcome) = welcome {
            theirs.write_all(welcome.as_bytes()).await.unwrap();
        }
        if !close {
            std::future::pending::<()>().await;
        }
    });
    Dashboard::connect(ours, "ur-test", Duration::from_secs(2))
        .await
        .unwrap_err()
}

#[tokio::test(start_paused = true)]
async fn a_wrong_welcome_silence_and_a_closed_line_are_errors() {
    let wrong = scripted(Some("SSH-2.0-OpenSSH\n"), false).await;
    assert!(matches!(wrong, DashboardError::Failed { .. }), "{wrong}");
    let silent = scripted(None, false).await;
    assert!(matches!(silent, DashboardError::Timeout { .. }), "{silent}");
    let closed = scripted(None, true).await;
    assert!(matches!(closed, DashboardError::Closed { .. }), "{closed}");
    for error in [wrong, silent, closed] {
        assert!(error.to_string().contains("ur-test"), "{error}");
    }
}

#[test]
fn ur_rtde_drives_the_fake_dashboard() {
    for profile in [Profile::Cb3, Profile::ESeries] {
        let fake = FakeController::start(profile);
        fake.power_off();
        fake.protective_stop(Duration::from_secs(6));
        let stdout = peers::run("ur_rtde_dashboard.py", &[&fake.host]);
        let step = |name: &str| peers::field(&stdout, name);
        assert!(!stdout.contains("error"), "{profile:?}: {stdout}");
        assert!(
            step("version").contains(&profile.version().to_string()),
            "{stdout}"
        );
        assert!(step("mode before").contains("POWER_OFF"), "{stdout}");
        assert!(step("mode after").contains("RUNNING"), "{stdout}");
        assert!(step("safety").contains("PROTECTIVE_STOP"), "{stdout}");
        assert!(step("safety after").contains("NORMAL"), "{stdout}");
        let arm = fake.arm();
        assert_eq!(arm.robot_mode, "RUNNING");
        assert_eq!(arm.program.as_deref(), Some("pick.urp"));
        assert!(!arm.playing, "stopped last");
    }
}
