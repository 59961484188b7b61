//! SIGTERM, as Slurm and Kubernetes stop a job, ends `yarok run` as Ctrl-C does: the recordings
//! are whole (the MCAP file has its summary for the third-party `mcap` reader, the joints CSV
//! only whole rows, the MP4 plays to its last frame in `ffprobe` even when the signal reached
//! the encoder too, as a scheduler signals the whole job), a real arm on the fake controller
//! gets its `stopj`, and the exit status is the conventional 143. An encoder that stops reading
//! frames neither blocks the run nor a Ctrl-C, and is not left running.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use yarok_test::peers;
use yarok_test::ur_controller;

use ur_controller::{FakeController, Profile};
use yarok_test::assert_says;

/// `yarok run` with `arguments`, in a process group of its own (as a scheduler's job is), its
/// standard error kept.
fn yarok_command(arguments: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_yarok"));
    command
        .arg("run")
        .args(arguments)
        .process_group(0)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    command
}

/// [`yarok_command`], started.
fn yarok_run(arguments: &[&str]) -> Child {
    yarok_command(arguments).spawn().unwrap()
}

/// The file yarok is writing as the output `path` until it puts it there (a hidden name beside
/// it), if there is one.
fn being_written(path: &Path) -> Option<PathBuf> {
    let name = path.file_name()?.to_string_lossy().into_owned();
    std::fs::read_dir(path.parent()?)
        .ok()?
        .filter_map(Result::ok)
        .map(|entry| entry.path())
        .find(|beside| {
            let beside = beside.file_name().unwrap_or_default().to_string_lossy();
            beside.starts_with(&format!(".{name}.")) && beside.ends_with(".yarok-writing")
        })
}

/// Waits until `ready` holds, failing if the run ends first or a minute passes.
fn wait_until(child: &mut Child, mut ready: impl FnMut() -> bool) {
    let started = Instant::now();
    while !ready() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before the signal"
        );
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "the run never got under way"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Sends SIGTERM to `target` (a pid, or `-pgid` for a whole group) and returns the run's exit
/// code, its standard error and how long it took to exit (at most 10 s).
fn terminate(child: Child, target: &str) -> (Option<i32>, String, Duration) {
    signal(child, "-TERM", target, Duration::from_secs(10))
}

/// Sends `signal` (`-TERM`, `-INT`) to `target` and returns the run's exit code, its standard
/// error and how long it took to exit, failing if that is more than `limit`.
fn signal(
    mut child: Child,
    signal: &str,
    target: &str,
    limit: Duration,
) -> (Option<i32>, String, Duration) {
    let status = Command::new("kill")
        .args([signal, "--", target])
        .status()
        .unwrap();
    assert!(status.success());
    let signalled = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if signalled.elapsed() > limit {
            child.kill().unwrap();
            panic!("{signal} did not end the run within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let took = signalled.elapsed();
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    (status.code(), stderr, took)
}

#[test]
fn sigterm_ends_a_recorded_run_with_its_files_whole() {
    let folder = tempfile::tempdir().unwrap();
    let mcap = folder.path().join("run.mcap");
    let csv = folder.path().join("joints.csv");
    let mut child = yarok_run(&[
        "pick_and_place_world",
        "--behaviour",
        "idle",
        "--record",
        mcap.to_str().unwrap(),
        "--set",
        &format!("plugins/joints_csv/path={:?}", csv.display().to_string()),
        "--set",
        "behaviour/seconds=600",
    ]);
    // Until the run is well under way: the CSV holds rows.
    wait_until(&mut child, || {
        being_written(&csv)
            .and_then(|file| std::fs::read_to_string(file).ok())
            .map_or(0, |text| text.lines().count())
            >= 20
    });
    let pid = child.id().to_string();
    let (code, stderr, took) = terminate(child, &pid);
    assert_eq!(code, Some(143), "{stderr}");
    assert_says(&stderr, &["SIGTERM"]);
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

/// Slurm's `scancel` signals every process of the job: the encoder gets SIGTERM with yarok.
/// The MP4 still plays, every frame decoding, and the run reports the signal.
#[test]
fn sigterm_to_a_filmed_runs_whole_job_leaves_a_playable_mp4() {
    let folder = tempfile::tempdir().unwrap();
    let video = folder.path().join("run.mp4");
    let mut child = yarok_run(&[
        "pick_and_place_world",
        "--behaviour",
        "idle",
        "--video",
        video.to_str().unwrap(),
        "--set",
        "plugins/video/size=[160, 120]",
        "--set",
        "behaviour/seconds=600",
    ]);
    // The encoder has the file open; frames are being sent to it.
    wait_until(&mut child, || being_written(&video).is_some());
    std::thread::sleep(Duration::from_millis(1500));
    let group = format!("-{}", child.id());
    let (code, stderr, took) = terminate(child, &group);
    assert_eq!(code, Some(143), "{stderr}");
    println!("from SIGTERM to exit, video closed: {took:?}");
    let probe = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args(["-show_entries", "stream=nb_read_frames,codec_name"])
        .args(["-of", "default=nw=1"])
        .arg(&video)
        .output()
        .unwrap();
    let probed = String::from_utf8_lossy(&probe.stdout);
    assert!(
        probe.status.success() && probe.stderr.is_empty(),
        "{probed}{}",
        String::from_utf8_lossy(&probe.stderr)
    );
    assert_says(&probed, &["codec_name=h264"]);
    let frames: u32 = probed
        .lines()
        .find_map(|line| line.strip_prefix("nb_read_frames="))
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no frame count: {probed}"));
    assert!(frames > 0, "{probed}");
}

/// A real-environment run (a UR5e and its 2F-85 on the fake controller, recording) stopped by
/// SIGTERM: the arm gets its stopj, the recording is whole, and the exit status is 143.
#[test]
fn sigterm_stops_a_real_arm_and_closes_its_recording() {
    let fake = FakeController::start(Profile::ESeries);
    let folder = tempfile::tempdir().unwrap();
    let mcap = folder.path().join("real.mcap");
    let host = format!("\"{}\"", fake.host);
    let mut child = yarok_run(&[
        "pick_and_place_world",
        "--env",
        "real",
        "--behaviour",
        "idle",
        "--record",
        mcap.to_str().unwrap(),
        "--set",
        &format!("interfaces/arm/host={host}"),
        "--set",
        &format!("interfaces/arm/gripper/host={host}"),
        "--set",
        "behaviour/seconds=600",
    ]);
    // Every component bound (the arm's stop registered): the recorder, started after binding,
    // has created its file.
    wait_until(&mut child, || {
        fake.rtde_connections() > 0 && fake.asked().len() >= 4 && being_written(&mcap).is_some()
    });
    std::thread::sleep(Duration::from_millis(500));
    assert!(fake.scripts().iter().all(|s| !s.starts_with("stopj")));
    let pid = child.id().to_string();
    let (code, stderr, took) = terminate(child, &pid);
    assert_eq!(code, Some(143), "{stderr}");
    assert_says(&stderr, &["SIGTERM"]);
    println!("from SIGTERM to exit, arm stopped: {took:?}");
    // yarok wrote stopj before it exited; the fake reads it on a task of its own.
    let stopped = |scripts: &[String]| scripts.iter().any(|s| s == "stopj(2.0)");
    let exited = Instant::now();
    while !stopped(&fake.scripts()) && exited.elapsed() < Duration::from_secs(2) {
        std::thread::sleep(Duration::from_millis(10));
    }
    assert!(stopped(&fake.scripts()), "no stopj: {:?}", fake.scripts());
    let summary = peers::run("mcap_summary.py", &[mcap.to_str().unwrap()]);
    // In `real` the recorder has the run's log channel (joints and bodies are recorded in
    // `sim`); what matters here is that the file ends with its summary.
    let line = peers::field(&summary, "summary");
    let channels: usize = line
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no summary: {summary}"));
    assert!(channels > 0, "{summary}");
}

/// An encoder that takes no frame (here a stand-in `ffmpeg` on the `PATH` that only sleeps):
/// the run, and a Ctrl-C sent while it waits, end within seconds with an error that says the
/// encoder stalled, and the encoder is stopped, not left running.
#[test]
fn an_encoder_that_stops_reading_neither_blocks_the_run_nor_outlives_it() {
    let folder = tempfile::tempdir().unwrap();
    let pid_file = folder.path().join("encoder.pid");
    let stand_in = folder.path().join("ffmpeg");
    std::fs::write(
        &stand_in,
        format!(
            "#!/bin/sh\necho $$ > '{}'\nexec sleep 600\n",
            pid_file.display()
        ),
    )
    .unwrap();
    std::fs::set_permissions(
        &stand_in,
        std::os::unix::fs::PermissionsExt::from_mode(0o755),
    )
    .unwrap();
    let path = format!(
        "{}:{}",
        folder.path().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let video = folder.path().join("run.mp4");
    let mut child = yarok_command(&[
        "pick_and_place_world",
        "--behaviour",
        "idle",
        "--video",
        video.to_str().unwrap(),
        "--set",
        "plugins/video/size=[160, 120]",
        "--set",
        "behaviour/seconds=600",
    ])
    .env("PATH", path)
    .spawn()
    .unwrap();
    wait_until(&mut child, || pid_file.exists());
    std::thread::sleep(Duration::from_millis(500));
    let encoder = std::fs::read_to_string(&pid_file)
        .unwrap()
        .trim()
        .to_owned();
    let pid = child.id().to_string();
    let (code, stderr, took) = signal(child, "-INT", &pid, Duration::from_secs(30));
    assert_ne!(code, Some(0), "{stderr}");
    assert_says(&stderr, &["encoder took no frame"]);
    println!("ended {took:?} after Ctrl-C: {stderr}");
    let alive = Command::new("kill")
        .args(["-0", &encoder])
        .stderr(Stdio::null())
        .status()
        .unwrap();
    assert!(!alive.success(), "the encoder {encoder} still runs");
}
