//! The fake controller's RTDE server is faithful enough for a third-party client: ur_rtde's
//! RTDEReceiveInterface (from PyPI, run as a separate process by
//! `scripts/peers/ur_rtde_receive.py`; `scripts/setup-test-peers.sh` installs it) connects to
//! it in both profiles — it negotiates, asks for its own long recipe at 125 or 500 Hz, starts —
//! and reads the joint positions the fake arm holds, within 1e-6 rad, and its modes; its
//! RTDEIOInterface sets up its sixteen input recipes and writes a digital output, the speed
//! slider and a register, which the fake receives.

use yarok_hw::ur::rtde::Value;

use yarok_test::peers;
use yarok_test::ur_controller;

use ur_controller::{FakeController, Profile};

#[test]
fn ur_rtde_reads_the_fake_arms_joints_in_both_profiles() {
    for profile in [Profile::Cb3, Profile::ESeries] {
        let fake = FakeController::start(profile);
        let q = [0.25, -1.1, 1.9, -2.3, -1.57, 3.0];
        fake.set_joints(q);
        let stdout = peers::run("ur_rtde_receive.py", &[&fake.host]);
        let read = |name: &str| peers::numbers(&stdout, name);
        let got = read("q");
        assert_eq!(got.len(), 6, "{stdout}");
        for (got, want) in got.iter().zip(q) {
            assert!((got - want).abs() <= 1e-6, "{profile:?}: {got} for {want}");
        }
        assert_eq!(read("robot_mode"), [7.0], "{stdout}");
        assert_eq!(read("safety_mode"), [1.0], "{stdout}");
        assert!(read("timestamp")[0] > 0.0, "{stdout}");
        let asked = fake.asked();
        assert!(asked.len() >= 50, "ur_rtde's recipe: {asked:?}");
    }
}

#[test]
fn ur_rtde_writes_outputs_and_registers_to_the_fake() {
    let fake = FakeController::start(Profile::ESeries);
    let stdout = peers::run("ur_rtde_io.py", &[&fake.host]);
    assert!(stdout.contains("done"), "{stdout}");
    // The values arrive on the fake's thread a moment after the client's last write.
    let arrived = |name: &str, value: Value| {
        let started = std::time::Instant::now();
        while fake.input(name) != Some(value) && started.elapsed().as_secs() < 2 {
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        fake.input(name) == Some(value)
    };
    assert!(arrived(
        "standard_digital_output_mask",
        Value::Uint8(1 << 2)
    ));
    assert!(arrived("standard_digital_output", Value::Uint8(1 << 2)));
    assert!(arrived("speed_slider_fraction", Value::Double(0.5)));
    assert!(arrived("input_double_register_18", Value::Double(0.25)));
}
