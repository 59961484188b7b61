//! The `joints_csv` plugin records a run of the `pendulum_clock` example: one row per tick, and
//! the angles the behaviour printed when each pendulum reached its target.

use std::path::PathBuf;
use std::process::Command;

/// The example's binary, built beside this test (`cargo test` builds examples), or built now.
fn pendulum_clock() -> PathBuf {
    let deps = std::env::current_exe().unwrap();
    let profile = deps.parent().and_then(|d| d.parent()).unwrap();
    let example = profile.join("examples").join("pendulum_clock");
    if !example.is_file() {
        let status = Command::new(env!("CARGO"))
            .args(["build", "--example", "pendulum_clock"])
            .status()
            .unwrap();
        assert!(status.success());
    }
    example
}

/// `left reached 0.5 rad at t = 0.93 s` → ("left", 0.5, 0.93).
fn reached(line: &str) -> Option<(String, f64, f64)> {
    let (name, rest) = line.split_once(" reached ")?;
    let (target, rest) = rest.split_once(" rad at t = ")?;
    let time = rest.strip_suffix(" s")?;
    Some((
        name.trim_start_matches('/').to_owned(),
        target.parse().ok()?,
        time.parse().ok()?,
    ))
}

#[test]
fn the_joint_recorder_writes_one_row_per_tick_with_the_angles_the_behaviour_saw() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("clock.csv");
    let output = Command::new(pendulum_clock())
        .args([
            "--set",
            &format!("plugins/joints_csv/path={}", csv.display()),
        ])
        .output()
        .unwrap();
    yarok_test::assert_succeeded(&output);
    let stdout = String::from_utf8(output.stdout).unwrap();
    let printed: Vec<(String, f64, f64)> = stdout.lines().filter_map(reached).collect();
    assert_eq!(printed.len(), 6, "{stdout}");

    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "time",
            "left/hinge.pos",
            "left/hinge.vel",
            "right/hinge.pos",
            "right/hinge.vel"
        ]
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|line| line.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let timestep = 0.002;
    for (index, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len());
        let expected = (index + 1) as f64 * timestep;
        assert!(
            (row[0] - expected).abs() < 1e-9,
            "row {index} is tick {}: time {}",
            index + 1,
            row[0]
        );
    }
    let last = printed.iter().map(|(_, _, t)| *t).fold(0.0, f64::max);
    let end = rows.last().unwrap()[0];
    assert!(
        (end - (last + 0.5)).abs() < 0.011,
        "the run ends 0.5 s after the last arrival: {end} vs {last}"
    );
    for (name, target, time) in &printed {
        let column = header
            .iter()
            .position(|h| *h == format!("{name}/hinge.pos"))
            .unwrap();
        // The time is printed to 0.01 s: the arrival tick is among the rows within 5 ms.
        let near: Vec<&Vec<f64>> = rows
            .iter()
            .filter(|row| (row[0] - time).abs() <= 0.005 + 1e-9)
            .collect();
        assert!(!near.is_empty());
        assert!(
            near.iter().any(|row| (row[column] - target).abs() < 0.011),
            "{name} at {time} s: expected about {target}, recorded {:?}",
            near.iter().map(|row| row[column]).collect::<Vec<_>>()
        );
    }
}

/// The recorder replaces a CSV it wrote, and refuses (keeping it byte for byte) a user's CSV.
#[test]
fn the_joint_recorder_replaces_only_a_csv_it_wrote() {
    let dir = tempfile::tempdir().unwrap();
    let run = |csv: &std::path::Path| {
        Command::new(pendulum_clock())
            .args([
                "--set",
                &format!("plugins/joints_csv/path={}", csv.display()),
            ])
            .output()
            .unwrap()
    };
    let ours = dir.path().join("clock.csv");
    yarok_test::assert_succeeded(&run(&ours));
    let first = std::fs::read(&ours).unwrap();
    yarok_test::assert_succeeded(&run(&ours));
    assert_eq!(
        std::fs::read(&ours).unwrap(),
        first,
        "a rerun writes the same rows"
    );

    let users = dir.path().join("measurements.csv");
    let theirs = "time,force\n0.0,1.5\n";
    std::fs::write(&users, theirs).unwrap();
    let output = run(&users);
    assert!(!output.status.success());
    yarok_test::assert_says(
        String::from_utf8_lossy(&output.stderr),
        &[
            &users.display().to_string(),
            "is not a joints CSV yarok wrote",
        ],
    );
    assert_eq!(std::fs::read_to_string(&users).unwrap(), theirs);
}
