//! The secondary interface: the client against the fake controller in both profiles (the
//! version message, joints, the arm's kinematics from its controller, a `movej` that runs in
//! time with the program flag up, `stopj`); a script sent as the program exits reaching a
//! controller that writes before it reads and drops a connection it cannot write to; 100 000 generated packets — real layouts mutated,
//! unknown and malformed sub-packages, arbitrary bytes — through the parser, never a panic;
//! and python-urx (a third-party client, run as a separate process) reading and moving the
//! fake CB3 arm, and reading its joints from the real-time interface (port 30003) in both
//! profiles.

use std::time::{Duration, Instant};

use tokio::net::TcpStream;
use yarok_hw::ur::secondary::{Packet, PacketError, Secondary, parse, take_packet};

use yarok_test::generator;
use yarok_test::peers;
use yarok_test::ur_controller;

use generator::Generator;
use ur_controller::{FakeController, Profile, SECONDARY_PORT};

async fn connect(fake: &FakeController) -> Secondary<TcpStream> {
    let stream = TcpStream::connect((fake.host.as_str(), SECONDARY_PORT))
        .await
        .unwrap();
    Secondary::connect(stream, fake.host.clone(), Duration::from_secs(1))
        .await
        .unwrap()
}

#[tokio::test]
async fn states_kinematics_and_a_movej_in_both_profiles() {
    for (profile, d1) in [(Profile::Cb3, 0.089159), (Profile::ESeries, 0.1625)] {
        let fake = FakeController::start(profile);
        let start = [0.1, -1.5, 1.4, -1.2, -1.6, 0.3];
        fake.set_joints(start);
        let mut secondary = connect(&fake).await;
        let version = secondary.version().expect("the version message came first");
        assert_eq!(version.project, "URControl");
        assert_eq!(u32::from(version.major), profile.version().major);

        let state = secondary.next_state().await.unwrap();
        let mode = state.mode.unwrap();
        assert_eq!(mode.robot_mode, 7);
        assert!(mode.power_on && !mode.program_running);
        let q: Vec<f64> = state.joints.unwrap().iter().map(|j| j.q_actual).collect();
        assert_eq!(q, start);
        let kinematics = state.kinematics.unwrap();
        assert_eq!(kinematics.dh_d[0], d1, "{profile:?}");

        let target = [0.6, -1.5, 1.4, -1.2, -1.6, 0.3];
        secondary
            .send_script("movej([0.6, -1.5, 1.4, -1.2, -1.6, 0.3], a=1.4, v=1.0)")
            .await
            .unwrap();
        let started = Instant::now();
        let mut saw_running = false;
        loop {
            let state = secondary.next_state().await.unwrap();
            let mode = state.mode.unwrap();
            saw_running |= mode.program_running;
            let q0 = state.joints.unwrap()[0].q_actual;
            if !mode.program_running && (q0 - target[0]).abs() < 1e-9 {
                break;
            }
            assert!(started.elapsed() < Duration::from_secs(3), "never arrived");
        }
        assert!(saw_running, "the program flag was up while moving");
        // 0.5 rad at 1 rad/s.
        assert!(
            started.elapsed() >= Duration::from_millis(400),
            "{:?}",
            started.elapsed()
        );
        assert_eq!(fake.joints(), target);
    }
}

#[tokio::test]
async fn stopj_stops_the_arm_where_it_is() {
    let fake = FakeController::start(Profile::ESeries);
    fake.set_joints([0.0; 6]);
    let mut secondary = connect(&fake).await;
    secondary
        .send_script("movej([2.0, 0, 0, 0, 0, 0], a=1.4, v=0.5)")
        .await
        .unwrap();
    tokio::time::sleep(Duration::from_millis(300)).await;
    secondary.send_script("stopj(2.0)").await.unwrap();
    tokio::time::sleep(Duration::from_millis(50)).await;
    let stopped = fake.joints()[0];
    assert!(stopped > 0.05 && stopped < 1.0, "{stopped}");
    tokio::time::sleep(Duration::from_millis(300)).await;
    assert_eq!(fake.joints()[0], stopped);
    assert_eq!(fake.scripts().len(), 2);
}

/// A robot state of sub-packages with the given content sizes and types.
/// A controller that writes to a connection before it reads from it, as UR's does (the version
/// message, then robot states), and drops a connection it cannot write to — here 100 ms in,
/// when the client may have closed; the line it read, or why it read none.
async fn greeting_controller(listener: tokio::net::TcpListener) -> Result<String, String> {
    use tokio::io::{AsyncBufReadExt, AsyncWriteExt};
    let (mut stream, _) = listener.accept().await.map_err(|e| e.to_string())?;
    let _greeted = stream.write_all(&[0; 2048]).await;
    tokio::time::sleep(Duration::from_millis(100)).await;
    stream
        .write_all(&[0; 2048])
        .await
        .map_err(|e| format!("dropped before reading: {e}"))?;
    let mut line = String::new();
    let mut reader = tokio::io::BufReader::new(stream);
    match reader.read_line(&mut line).await {
        Ok(_) if !line.is_empty() => Ok(line),
        Ok(_) => Err("the connection closed with no line".into()),
        Err(error) => Err(error.to_string()),
    }
}

#[tokio::test]
async fn a_script_sent_as_the_program_exits_reaches_a_controller_that_greets_first() {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap();
    let controller = tokio::spawn(greeting_controller(listener));
    let mut stream = TcpStream::connect(address).await.unwrap();
    // The greeting arrives before the client sends; the controller writes again before it reads.
    tokio::time::sleep(Duration::from_millis(20)).await;
    yarok_hw::ur::secondary::send_script_and_close(
        &mut stream,
        "stopj(2.0)",
        Duration::from_millis(250),
    )
    .await
    .unwrap();
    drop(stream);
    assert_eq!(controller.await.unwrap(), Ok("stopj(2.0)\n".to_owned()));
}

#[tokio::test]
async fn without_draining_the_greeting_the_controller_loses_the_script() {
    // What `send_script_and_close` exists for: the same exchange, closed at once, with the
    // greeting unread (the connection is reset, and the controller's next write fails).
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap();
    let controller = tokio::spawn(greeting_controller(listener));
    let mut stream = TcpStream::connect(address).await.unwrap();
    tokio::time::sleep(Duration::from_millis(20)).await;
    yarok_hw::ur::secondary::send_script(&mut stream, "stopj(2.0)")
        .await
        .unwrap();
    drop(stream);
    let read = controller.await.unwrap();
    assert!(
        read.as_ref()
            .is_err_and(|e| e.starts_with("dropped before reading")),
        "{read:?}"
    );
}

fn robot_state(sub_packages: &[(u8, usize)], generator: &mut Generator) -> Vec<u8> {
    let mut body = Vec::new();
    for &(kind, size) in sub_packages {
        body.extend(((size + 5) as i32).to_be_bytes());
        body.push(kind);
        body.extend((0..size).map(|_| generator.next_u64() as u8));
    }
    let mut out = ((body.len() + 5) as i32).to_be_bytes().to_vec();
    out.push(16);
    out.extend(body);
    out
}

#[test]
fn a_hundred_thousand_generated_packets_never_panic() {
    let mut generator = Generator(0x2545_F491_4F6C_DD1D);
    // The CB3 layout's content sizes, and an e-Series one's, then unknown sub-packages.
    let layouts: [&[(u8, usize)]; 3] = [
        &[
            (0, 41),
            (1, 246),
            (2, 32),
            (3, 69),
            (4, 96),
            (5, 220),
            (7, 56),
            (8, 3),
        ],
        &[
            (0, 42),
            (1, 246),
            (2, 32),
            (3, 70),
            (4, 96),
            (5, 220),
            (7, 56),
            (8, 4),
        ],
        &[(0, 41), (42, 17), (1, 246), (200, 0), (4, 96)],
    ];
    let mut parsed = 0;
    for round in 0..100_000 {
        let layout = layouts[round % layouts.len()];
        let mut bytes = robot_state(layout, &mut generator);
        match generator.below(4) {
            0 => {}
            1 => {
                let at = generator.below(bytes.len());
                bytes[at] ^= generator.next_u64() as u8 | 1;
            }
            2 => {
                let keep = generator.below(bytes.len());
                bytes.truncate(keep);
                // Keep the outer size honest, so the sub-packages are what break.
                if keep >= 5 {
                    bytes[..4].copy_from_slice(&(keep as i32).to_be_bytes());
                }
            }
            _ => {
                let length = generator.below(64);
                bytes = (0..length).map(|_| generator.next_u64() as u8).collect();
            }
        }
        let mut buffer = bytes;
        while let Ok(Some(packet)) = take_packet(&mut buffer) {
            if let Ok(Packet::RobotState(_)) = parse(&packet) {
                parsed += 1;
            }
        }
    }
    assert!(parsed > 20_000, "only {parsed} robot states parsed");
    assert_eq!(
        take_packet(&mut vec![0, 0, 0, 2, 16]),
        Err(PacketError::Size(2))
    );
    let short_joints = robot_state(&[(1, 40)], &mut generator);
    assert!(matches!(
        parse(&short_joints),
        Err(PacketError::Truncated { .. })
    ));
}

#[test]
fn urx_reads_and_moves_the_fake_cb3_arm() {
    let fake = FakeController::start(Profile::Cb3);
    let start = [0.0, -1.57, 1.57, -1.57, -1.57, 0.0];
    fake.set_joints(start);
    let target = [0.4, -1.4, 1.5, -1.6, -1.57, 0.2];
    let target_args = target.map(|q| q.to_string());
    let mut args = vec![fake.host.as_str()];
    args.extend(target_args.iter().map(String::as_str));
    let stdout = peers::run("urx_movej.py", &args);
    let read = |name: &str| peers::numbers(&stdout, name);
    for (got, want) in read("before:").iter().zip(start) {
        assert!((got - want).abs() <= 1e-6, "{stdout}");
    }
    for (got, want) in read("after:").iter().zip(target) {
        assert!((got - want).abs() <= 0.01, "urx's threshold: {stdout}");
    }
    assert!(stdout.contains("running: True"), "{stdout}");
    let scripts = fake.scripts();
    assert!(
        scripts.iter().any(|s| s.starts_with("movej(")),
        "{scripts:?}"
    );
}

#[test]
fn urx_reads_the_fake_arms_joints_from_the_real_time_interface() {
    for profile in [Profile::Cb3, Profile::ESeries] {
        let fake = FakeController::start(profile);
        let q = [0.2, -1.3, 1.4, -1.5, -1.6, 0.7];
        fake.set_joints(q);
        let stdout = peers::run("urx_realtime.py", &[&fake.host]);
        let got = peers::numbers(&stdout, "q:");
        assert_eq!(got.len(), 6, "{stdout}");
        for (got, want) in got.iter().zip(q) {
            assert!((got - want).abs() <= 1e-6, "{profile:?}: {stdout}");
        }
    }
}

/// A loop that remakes `next_state` each time round a `select!` beside a faster stream (as the
/// arm's driver does beside RTDE) still finds the secondary interface gone silent: the limit
/// counts from the last robot state, not from each call.
#[tokio::test(start_paused = true)]
async fn silence_is_found_though_the_call_is_made_again_and_again() {
    let (ours, mut theirs) = tokio::io::duplex(1024);
    // A robot state without sub-packages, then nothing more.
    tokio::io::AsyncWriteExt::write_all(&mut theirs, &[0, 0, 0, 5, 16])
        .await
        .unwrap();
    let silence = Duration::from_secs(1);
    let mut secondary = Secondary::connect(ours, "fake", silence).await.unwrap();
    let started = tokio::time::Instant::now();
    let mut ticks = 0u32;
    let error = loop {
        tokio::select! {
            state = secondary.next_state() => break state.unwrap_err(),
            () = tokio::time::sleep(Duration::from_millis(8)) => ticks += 1,
        }
        assert!(started.elapsed() < silence * 3, "silence never found");
    };
    assert!(
        error.to_string().contains("no robot state within 1 s"),
        "{error}"
    );
    assert_eq!(started.elapsed(), silence);
    assert!(ticks > 100, "{ticks}");
    drop(theirs);
}
