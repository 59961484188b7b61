//! The RTDE client against the project's fake controller over TCP (both profiles: version,
//! an output recipe streamed at its rate, joint positions as the arm holds them, unknown
//! variables named, inputs written) and against scripted controllers over an in-memory pipe
//! (a refused protocol version, silence and a closed connection are errors naming the
//! controller, never hangs).

use std::time::Duration;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use yarok_hw::ur::rtde::{Reply, Rtde, RtdeError, RtdeSettings, Value};

use yarok_test::ur_controller;

use ur_controller::{FakeController, Profile, RTDE_PORT};

async fn connect(fake: &FakeController) -> Rtde<TcpStream> {
    let stream = TcpStream::connect((fake.host.as_str(), RTDE_PORT))
        .await
        .unwrap();
    Rtde::connect(stream, RtdeSettings::new(fake.host.clone()))
        .await
        .unwrap()
}

#[tokio::test]
async fn joint_positions_stream_at_the_recipes_rate_in_both_profiles() {
    for (profile, rate) in [(Profile::Cb3, 125.0), (Profile::ESeries, 500.0)] {
        let fake = FakeController::start(profile);
        let q = [0.1, -1.2, 1.3, -1.4, 1.5, -1.6];
        fake.set_joints(q);
        let mut rtde = connect(&fake).await;
        assert_eq!(rtde.controller_version(), profile.version());
        let recipe = rtde
            .setup_outputs(rate, &["timestamp", "actual_q", "robot_mode", "joint_mode"])
            .await
            .unwrap();
        assert_eq!(recipe.variables.len(), 4);
        rtde.start().await.unwrap();
        let mut times = Vec::new();
        for _ in 0..50 {
            let values = rtde.receive().await.unwrap();
            let [
                Value::Double(time),
                Value::Vector6d(got),
                Value::Int32(7),
                Value::Vector6Int32([253, ..]),
            ] = values[..]
            else {
                panic!("{values:?}");
            };
            assert_eq!(got, q);
            times.push(time);
        }
        let span = times[49] - times[0];
        let period = span / 49.0;
        assert!(
            (period - 1.0 / rate).abs() < 0.5 / rate,
            "{profile:?}: {period} s between packages at {rate} Hz"
        );
        rtde.pause().await.unwrap();
    }
}

#[tokio::test]
async fn unknown_variables_are_named_and_inputs_reach_the_controller() {
    let fake = FakeController::start(Profile::ESeries);
    let mut rtde = connect(&fake).await;
    let error = rtde
        .setup_outputs(500.0, &["actual_q", "actual_Q", "output_int_register_99"])
        .await
        .unwrap_err();
    assert!(
        matches!(&error, RtdeError::NotFound { names, .. }
            if names == &["actual_Q", "output_int_register_99"]),
        "{error}"
    );
    let message = error.to_string();
    assert!(
        message.contains(&fake.host) && message.contains("5.11.1"),
        "{message}"
    );

    let inputs = rtde
        .setup_inputs(&["input_double_register_24", "input_int_register_24"])
        .await
        .unwrap();
    rtde.send(&inputs, &[Value::Double(0.25), Value::Int32(-3)])
        .await
        .unwrap();
    let wrong = rtde
        .send(&inputs, &[Value::Double(0.25)])
        .await
        .unwrap_err();
    assert!(matches!(wrong, RtdeError::Recipe { .. }), "{wrong}");
    rtde.setup_outputs(500.0, &["input_double_register_24"])
        .await
        .unwrap();
    rtde.start().await.unwrap();
    // The input arrives before later packages.
    let mut seen = None;
    for _ in 0..50 {
        if let [Value::Double(value)] = rtde.receive().await.unwrap()[..]
            && value != 0.0
        {
            seen = Some(value);
            break;
        }
    }
    assert_eq!(seen, Some(0.25));
    assert_eq!(fake.input("input_int_register_24"), Some(Value::Int32(-3)));
}

/// A controller that answers the protocol request with `answer` and then does nothing.
async fn scripted(
    answer: Option<Reply>,
    close: bool,
) -> Result<Rtde<tokio::io::DuplexStream>, RtdeError> {
    let (ours, mut theirs) = tokio::io::duplex(1024);
    tokio::spawn(async move {
        let mut request = [0u8; 5];
        theirs.read_exact(&mut request).await.unwrap();
        assert_eq!(request, [0, 5, b'V', 0, 2]);
        if let Some(answer) = answer {
            theirs.write_all(&answer.encode().unwrap()).await.unwrap();
        }
        if !close {
            std::future::pending::<()>().await;
        }
    });
    let mut settings = RtdeSettings::new("ur-test");
    settings.reply_timeout = Duration::from_secs(2);
    Rtde::connect(ours, settings).await
}

#[tokio::test(start_paused = true)]
async fn refusals_silence_and_a_closed_line_are_errors_naming_the_controller() {
    let refused = scripted(Some(Reply::ProtocolVersion { accepted: false }), false)
        .await
        .unwrap_err();
    assert!(matches!(refused, RtdeError::Refused { .. }), "{refused}");
    let silent = scripted(None, false).await.unwrap_err();
    assert!(
        matches!(silent, RtdeError::Timeout { seconds: 2.0, .. }),
        "{silent}"
    );
    let closed = scripted(None, true).await.unwrap_err();
    assert!(matches!(closed, RtdeError::Closed { .. }), "{closed}");
    for error in [refused, silent, closed] {
        assert!(error.to_string().contains("ur-test"), "{error}");
    }
}
