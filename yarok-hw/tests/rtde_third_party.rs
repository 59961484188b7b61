//! The fake controller's RTDE server is faithful enough for a third-party client: ur_rtde's
//! RTDEReceiveInterface (from PyPI, run as a separate process by
//! `scripts/peers/ur_rtde_receive.py`; `scripts/setup-test-peers.sh` installs it) connects to
//! it in both profiles — it negotiates, asks for its own long recipe at 125 or 500 Hz, starts —
//! and reads the joint positions the fake arm holds, within 1e-6 rad, and its modes.

use std::process::Command;

#[path = "support/peers.rs"]
mod peers;
#[path = "support/ur_controller/mod.rs"]
mod ur_controller;

use ur_controller::{FakeController, Profile};

#[test]
fn ur_rtde_reads_the_fake_arms_joints_in_both_profiles() {
    for profile in [Profile::Cb3, Profile::ESeries] {
        let fake = FakeController::start(profile);
        let q = [0.25, -1.1, 1.9, -2.3, -1.57, 3.0];
        fake.set_joints(q);
        let output = Command::new(peers::python())
            .arg(peers::script("ur_rtde_receive.py"))
            .arg(&fake.host)
            .output()
            .expect("ur_rtde's script runs");
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(
            output.status.success(),
            "{profile:?}: {stdout}\n{}\nasked for {:?}",
            String::from_utf8_lossy(&output.stderr),
            fake.asked()
        );
        let read = |name: &str| -> Vec<f64> {
            let line = stdout
                .lines()
                .find_map(|line| line.strip_prefix(name)?.strip_prefix(' '))
                .unwrap_or_else(|| panic!("no {name} in {stdout}"));
            line.split(' ').map(|v| v.parse().unwrap()).collect()
        };
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
