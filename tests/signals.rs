//! SIGTERM, as Slurm and Kubernetes stop a job, ends `yarok run` as Ctrl-C does: the recordings
//! are whole (the MCAP file has its summary for the third-party `mcap` reader, the joints CSV
//! only whole rows), and the exit status is the conventional 143.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

#[path = "../yarok-hw/tests/support/peers.rs"]
mod peers;

#[test]
fn sigterm_ends_a_recorded_run_with_its_files_whole() {
    let folder = tempfile::tempdir().unwrap();
    let mcap = folder.path().join("run.mcap");
    let csv = folder.path().join("joints.csv");
    let mut child = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args([
            "run",
            "pick_and_place_world",
            "--behaviour",
            "idle",
            "--record",
        ])
        .arg(&mcap)
        .args([
            "--set",
            &format!("plugins/joints_csv/path={:?}", csv.display().to_string()),
        ])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Until the run is well under way: the CSV holds rows.
    let started = Instant::now();
    while std::fs::read_to_string(&csv).map_or(0, |text| text.lines().count()) < 20 {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before the signal"
        );
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "the run wrote no rows"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let signalled = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if signalled.elapsed() > Duration::from_secs(10) {
            child.kill().unwrap();
            panic!("SIGTERM did not end the run");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let took = signalled.elapsed();
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    assert_eq!(status.code(), Some(143), "{stderr}");
    assert!(stderr.contains("SIGTERM"), "{stderr}");
    println!("from SIGTERM to exit, files closed: {took:?}");

    let summary = peers::run("mcap_summary.py", &[mcap.to_str().unwrap()]);
    let line = peers::field(&summary, "summary");
    let [channels, messages]: [usize; 2] = line
        .split(' ')
        .map(|n| n.parse().unwrap_or_else(|_| panic!("no summary: {line}")))
        .collect::<Vec<_>>()
        .try_into()
        .unwrap();
    assert!(channels > 0 && messages > 0, "{summary}");

    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.ends_with('\n'), "the CSV ends mid-row");
    let mut rows = text.lines();
    let columns = rows.next().unwrap().split(',').count();
    for row in rows {
        let fields: Vec<&str> = row.split(',').collect();
        assert_eq!(fields.len(), columns, "a cut row: {row:?}");
        assert!(fields.iter().all(|f| f.parse::<f64>().is_ok()), "{row:?}");
    }
}
