//! `yarok run` runs the bundled worlds with their demo behaviours: it lists them, records a run
//! in MCAP, and refuses a world, a behaviour or an option it does not know with the nearest
//! name. (Every world's run is in `scripts/test.sh`, in release.)

use yarok_test::peers;
mod support;
use support::yarok_binary;

use yarok::components::demos;
use yarok_binary::{yarok, yarok_fails};
use yarok_test::assert_says;

#[test]
fn lists_every_bundled_world_with_its_behaviours() {
    let (code, stdout, _) = yarok(&["run", "--list"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), demos::demos().len(), "{stdout}");
    assert!(
        lines
            .iter()
            .any(|l| l.split_whitespace().collect::<Vec<_>>()
                == ["pick_and_place_world", "stack,", "idle"]),
        "{stdout}"
    );
}

#[test]
fn records_a_run_in_mcap() {
    let folder = tempfile::tempdir().unwrap();
    let file = folder.path().join("tower.mcap");
    let (code, stdout, stderr) = yarok(&[
        "run",
        "tower_world",
        "--record",
        file.to_str().unwrap(),
        "--set",
        "behaviour/seconds=0.5",
        "--set",
        "/tower/rows=2",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert_says(&stdout, &["t = 0.50 s: 250 ticks"]);
    let bytes = std::fs::read(&file).unwrap();
    let magic = b"\x89MCAP0\r\n";
    assert!(bytes.starts_with(magic) && bytes.ends_with(magic));
    let summary = peers::run("mcap_summary.py", &[file.to_str().unwrap()]);
    // Two rows of three blocks, each a body of its own in /tf.
    let frames = peers::field(&summary, "transforms");
    let blocks = frames
        .split(' ')
        .filter(|f| f.starts_with("tower/"))
        .count();
    assert_eq!(blocks, 6, "{frames}");
    assert!(
        summary.contains("t = 0.50 s: 250 ticks"),
        "the log line is recorded: {summary}"
    );
}

#[test]
fn unknown_names_get_the_nearest() {
    yarok_fails(
        &["run", "pick_and_plac_world"],
        2,
        &["did you mean `pick_and_place_world`"],
    );
    let (code, _, stderr) = yarok(&["run", "pick_and_place_world", "--behaviour", "stak"]);
    assert_eq!(code, 2);
    assert_says(&stderr, &["no behaviour \"stak\"; did you mean `stack`"]);
    yarok_fails(
        &["run", "empty_world", "--recrd", "x.mcap"],
        2,
        &["did you mean `--record`"],
    );
    yarok_fails(
        &["run", "empty_world", "--set", "behaviour/out=\"x\""],
        2,
        &["no config key `out` (it has seconds)"],
    );
}

#[test]
fn on_a_terminal_a_status_line_shows_time_speed_and_ticks() {
    // `script` runs the command on a pseudo-terminal of its own and copies what it shows.
    let command = format!(
        "{} run empty_world --set platform/realtime=true --set behaviour/seconds=0.8",
        env!("CARGO_BIN_EXE_yarok")
    );
    let output = std::process::Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .output()
        .expect("script (util-linux) runs");
    let shown = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{shown}");
    let status = shown
        .split('\r')
        .find(|line| line.contains("ticks/s"))
        .unwrap_or_else(|| panic!("no status line in {shown:?}"));
    // Paced to the wall clock: about real time, 500 ticks a second.
    let factor: f64 = status
        .split('×')
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|f| f.parse().ok())
        .unwrap_or_else(|| panic!("no real-time factor in {status:?}"));
    assert!((0.5..1.5).contains(&factor), "{status:?}");
    // Without a terminal, no status line.
    let (_, _, stderr) = yarok(&["run", "empty_world", "--set", "behaviour/seconds=0.1"]);
    assert!(!stderr.contains("ticks/s"), "{stderr}");
}

/// Two recorders given one file would overwrite or interleave each other: refused before the
/// run starts, naming both, and nothing is written.
#[test]
fn two_recorders_on_one_file_are_refused_before_the_run() {
    let folder = tempfile::tempdir().unwrap();
    let file = folder.path().join("run.out");
    let file = file.to_str().unwrap();
    let same_file_another_way = format!("{}/./run.out", folder.path().display());
    for args in [
        vec![
            "run",
            "pick_and_place_world",
            "--record",
            file,
            "--video",
            file,
        ],
        vec![
            "run",
            "pick_and_place_world",
            "--record",
            file,
            "--set",
            &format!("plugins/joints_csv/path={same_file_another_way:?}"),
        ],
    ] {
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
            .args(&args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert_says(&stderr, &["would both write"]);
        assert!(
            !std::path::Path::new(file).exists(),
            "{args:?} wrote the file"
        );
    }
}

/// `model_cache` takes true, false or a folder: `~/` is the home folder, and an empty path, a
/// quoted yes/true or a number are errors that say what it takes — never folders named
/// literally in the current directory.
#[test]
fn the_model_cache_setting_takes_true_false_or_a_folder() {
    let home = tempfile::tempdir().unwrap();
    let here = tempfile::tempdir().unwrap();
    let run = |value: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
            .args(["run", "pick_and_place_world", "--set"])
            .arg(format!("platform/model_cache={value}"))
            .env("HOME", home.path())
            .current_dir(here.path())
            .stdout(std::process::Stdio::null())
            .output()
            .unwrap()
    };
    for (value, expected) in [
        ("\"\"", "an empty path"),
        ("\"yes\"", "without them"),
        ("\"true\"", "without them"),
        ("3", "expected true, false or a folder's path"),
    ] {
        let output = run(value);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{value}: {stderr}");
        assert!(
            stderr.contains(expected) && stderr.contains("model_cache"),
            "{value}: {stderr}"
        );
    }
    let output = run("\"~/models\"");
    yarok_test::assert_succeeded(&output);
    let cached = std::fs::read_dir(home.path().join("models"))
        .unwrap()
        .count();
    assert_eq!(cached, 1, "one compiled model in ~/models");
    assert_eq!(
        std::fs::read_dir(here.path()).unwrap().count(),
        0,
        "nothing in the current folder"
    );
}

/// Built without the `camera` feature, a world whose sensors need it for `real` is refused
/// naming the feature, not only the environments the sensors have.
#[cfg(not(feature = "camera"))]
#[test]
fn a_real_run_that_needs_the_camera_feature_says_so() {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(["run", "digit_world", "--env", "real"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    for digit in ["/arm/gripper/left_digit", "/arm/gripper/right_digit"] {
        assert!(
            stderr.contains(&format!(
                "{digit} (Digit) supports sim, mock — build yarok with the `camera` feature"
            )),
            "{stderr}"
        );
    }
}

/// Interface settings the selected environment's interface never reads are warned about, naming
/// the component, the keys and where they were set.
#[test]
fn interface_settings_nothing_reads_are_warned_about() {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args([
            "run",
            "pick_and_place_world",
            "--behaviour",
            "idle",
            "--env",
            "mock",
        ])
        .args(["--set", "interfaces/arm/hots=\"x\""])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr.contains(
            "component /arm: its `mock` interface takes no settings; hots \
             (--set interfaces/arm/hots=\"x\") changed nothing"
        ),
        "{stderr}"
    );
}

/// A recording whose writes fail (a full disk: `/dev/full`) ends the run with an error naming
/// the file and why, whichever thread of the recorder met it.
#[test]
fn a_recording_on_a_full_disk_ends_the_run_naming_the_file() {
    yarok_fails(
        &[
            "run",
            "tower_world",
            "--record",
            "/dev/full",
            "--set",
            "behaviour/seconds=2",
        ],
        2,
        &[
            "plugin mcap (/dev/full) failed: cannot write /dev/full",
            "No space left on device",
        ],
    );
}

/// A video whose disk fills while its index is written at the end (ffmpeg then exits 0 and
/// leaves a file no player opens) ends the run with an error naming the file, as incomplete.
/// The disk is a small tmpfs in a mount namespace of the run's own (`unshare`, util-linux):
/// the run's whole video, less one page, fits on it.
#[test]
fn a_video_on_a_disk_that_fills_at_its_end_is_an_error_naming_the_file() {
    let folder = tempfile::tempdir().unwrap();
    let whole = folder.path().join("whole.mp4");
    let run = |video: &str| {
        [
            "run",
            "pick_and_place_world",
            "--behaviour",
            "idle",
            "--set",
            "behaviour/seconds=10",
            "--video",
            video,
        ]
        .map(str::to_owned)
    };
    let (code, _, stderr) = yarok(&run(whole.to_str().unwrap()).each_ref().map(String::as_str));
    assert_eq!(code, 0, "{stderr}");
    // 10 s of video make an index longer than a page, so a page boundary falls inside it.
    let size = std::fs::metadata(&whole).unwrap().len();
    let disk = folder.path().join("disk");
    std::fs::create_dir(&disk).unwrap();
    let clip = disk.join("clip.mp4");
    let script = format!(
        "mount -t tmpfs -o size={} tmpfs \"$1\" && shift && exec \"$@\"",
        (size - 1) / 4096 * 4096
    );
    let output = std::process::Command::new("unshare")
        .args(["--mount", "--map-root-user", "sh", "-c", &script, "sh"])
        .arg(&disk)
        .arg(env!("CARGO_BIN_EXE_yarok"))
        .args(run(clip.to_str().unwrap()))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert_says(
        &stderr,
        &[&format!("plugin video ({})", clip.display()), "incomplete"],
    );
}

#[test]
fn a_recorder_of_the_simulation_is_refused_in_mock_before_anything_runs() {
    let folder = tempfile::tempdir().unwrap();
    let csv = folder.path().join("joints.csv");
    let path = format!("plugins/joints_csv/path=\"{}\"", csv.display());
    let refused = format!(
        "plugin joints_csv ({}) cannot run in `mock`: it runs in sim",
        csv.display()
    );
    yarok_fails(
        &[
            "run",
            "pick_and_place_world",
            "--env",
            "mock",
            "--set",
            &path,
        ],
        2,
        &[&refused],
    );
    assert!(!csv.exists(), "nothing was recorded");
}

/// A non-UTF-8 argument (a path in Latin-1) is refused in every subcommand naming its
/// position, with exit status 2: never a panic.
#[test]
fn a_non_utf8_argument_is_refused_naming_it_in_every_subcommand() {
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;

    let latin1 = OsStr::from_bytes(b"caf\xe9.mcap");
    for (command, position) in [
        (
            vec![
                OsStr::new("run"),
                OsStr::new("digit_world"),
                OsStr::new("--record"),
                latin1,
            ],
            4,
        ),
        (vec![OsStr::new("compose"), latin1], 2),
        (
            vec![OsStr::new("tactile"), OsStr::new("calibrate"), latin1],
            3,
        ),
        (vec![latin1], 1),
    ] {
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
            .args(&command)
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{command:?}: {said}");
        assert!(
            said.contains(&format!(
                "argument {position} (\"caf\u{FFFD}.mcap\") is not UTF-8"
            )),
            "{command:?}: {said}"
        );
        assert!(!said.contains("panicked"), "{said}");
    }
}

/// `--config /dev/zero` and a template whose `<include>` is `/dev/zero` are refused at once,
/// naming the file and the limit, instead of reading until memory runs out.
#[test]
fn a_config_or_include_that_never_ends_is_refused_naming_the_limit() {
    let started = std::time::Instant::now();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(["run", "digit_world", "--config", "/dev/zero"])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{said}");
    assert!(
        said.contains("/dev/zero") && said.contains("more than 1 MiB"),
        "{said}"
    );
    let folder = tempfile::tempdir().unwrap();
    let world = folder.path().join("world.xml");
    std::fs::write(
        &world,
        r#"<mujoco><worldbody><include file="/dev/zero"/></worldbody></mujoco>"#,
    )
    .unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
        .arg("compose")
        .arg(&world)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{said}");
    assert!(
        said.contains("/dev/zero") && said.contains("more than 64 MiB"),
        "{said}"
    );
    assert!(started.elapsed() < std::time::Duration::from_secs(20));
}

/// A recording to a named pipe nobody reads is refused before the run, naming it, instead of
/// blocking forever on its first write.
#[test]
fn a_recording_to_a_pipe_nobody_reads_is_refused_before_the_run() {
    let folder = tempfile::tempdir().unwrap();
    let pipe = folder.path().join("recording.mcap");
    let made = std::process::Command::new("mkfifo")
        .arg(&pipe)
        .status()
        .unwrap();
    assert!(made.success());
    let started = std::time::Instant::now();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(["run", "digit_world", "--record"])
        .arg(&pipe)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{said}");
    assert!(said.contains("is a named pipe nobody reads"), "{said}");
    assert!(started.elapsed() < std::time::Duration::from_secs(30));
}

/// Two runs recording to one path: the second is refused naming the first's process, and the
/// first's recording is written whole.
#[test]
fn a_second_run_recording_to_the_same_path_is_refused_naming_the_first() {
    let folder = tempfile::tempdir().unwrap();
    let recording = folder.path().join("run.mcap");
    let lock = folder.path().join(".run.mcap.yarok-lock");
    let args = |seconds: &str| {
        [
            "run",
            "tower_world",
            "--behaviour",
            "idle",
            "--set",
            seconds,
            "--record",
            recording.to_str().unwrap(),
        ]
        .map(str::to_owned)
    };
    let mut first = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(args("behaviour/seconds=3"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while !lock.exists() && started.elapsed() < std::time::Duration::from_secs(30) {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    assert!(lock.exists(), "the first run took no lock");
    let second = std::process::Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(args("behaviour/seconds=0.1"))
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&second.stderr);
    assert!(!second.status.success(), "{said}");
    assert!(
        said.contains(&format!(
            "another yarok run (process {}) is writing",
            first.id()
        )),
        "{said}"
    );
    let status = first.wait().unwrap();
    assert!(status.success());
    assert!(!lock.exists(), "the first run left its lock");
    let bytes = std::fs::read(&recording).unwrap();
    assert!(bytes.starts_with(b"\x89MCAP0\r\n") && bytes.ends_with(b"\x89MCAP0\r\n"));
}
