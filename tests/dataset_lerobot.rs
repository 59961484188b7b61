//! `yarok run … --dataset DIR` (feature `dataset`) read back as LeRobot reads a v3 dataset, in a
//! process of its own (`scripts/peers/lerobot_read.py`: pyarrow, pandas, PyAV and numpy, written
//! from LeRobot's code): every episode's rows and indices, timestamps at the declared fps, every
//! frame's joint positions bit for bit those an MCAP recording of the same run holds of the same
//! tick, every video frame decoded and equal (to within H.264's loss) to the image the recording
//! holds of that tick, and every statistic equal to the one recomputed from the data and the
//! decoded frames.
#![cfg(feature = "dataset")]

use yarok_test::peers;

use std::path::Path;
use std::process::{Command, Output};
use yarok_test::{assert_says, assert_succeeded};

fn yarok(folder: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_yarok"))
        .current_dir(folder)
        .args(args)
        .output()
        .unwrap()
}

/// `lerobot_read.py`'s `matched` line for `key`: the lowest PSNR of a frame against its
/// recorded image, and the mean PSNR against its own image and against the next one.
fn matched(read: &str, key: &str) -> (f64, f64, f64) {
    let line = peers::field(read, &format!("matched {key}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let number = |name: &str| -> f64 {
        let at = words.iter().position(|w| *w == name).unwrap();
        words[at + 1].parse().unwrap()
    };
    (number("min_psnr"), number("own"), number("next"))
}

/// `lerobot_read.py`'s first line: episodes, frames, tasks and fps.
fn totals(read: &str) -> [u64; 4] {
    let words: Vec<&str> = read.lines().next().unwrap().split_whitespace().collect();
    let number = |name: &str| -> u64 {
        let at = words.iter().position(|w| *w == name).unwrap();
        words[at + 1].parse().unwrap()
    };
    ["episodes", "frames", "tasks", "fps"].map(number)
}

#[test]
fn a_digit_world_run_is_a_lerobot_dataset_whose_videos_are_the_recorded_images() {
    let folder = tempfile::tempdir().unwrap();
    let run = yarok(
        folder.path(),
        &[
            "run",
            "digit_world",
            "--dataset",
            "dataset",
            "--record",
            "run.mcap",
            "--set",
            "plugins/mcap/image_hz=30.0",
            "--set",
            "plugins/mcap/every=1",
            "--set",
            "plugins/mcap/cameras=[\"overview\"]",
            "--set",
            "plugins/mcap/size=[320, 240]",
            "--set",
            "plugins/dataset/cameras=[\"overview\"]",
            "--set",
            "plugins/dataset/size=[320, 240]",
        ],
    );
    assert_succeeded(&run);
    let dataset = folder.path().join("dataset");
    let mcap = folder.path().join("run.mcap");
    let read = peers::run(
        "lerobot_read.py",
        &[dataset.to_str().unwrap(), mcap.to_str().unwrap()],
    );

    // One episode (the behaviour begins none), at 30 frames a second of its 5.7 s.
    let [episodes, frames, tasks, fps] = totals(&read);
    assert_eq!((episodes, tasks, fps), (1, 1, 30), "{read}");
    assert!((150..200).contains(&frames), "{read}");
    assert_eq!(
        peers::field(&read, "episode 0"),
        format!("length {frames} tasks pick up the block and put it on the target"),
    );
    // Every frame's joint positions (the arm's six) are, bit for bit, those recorded at its
    // tick.
    assert_eq!(
        peers::field(&read, "states"),
        format!("{frames} equal to the recording's (joints 6)")
    );
    let keys = [
        "observation.images.arm.gripper.left_digit.image",
        "observation.images.arm.gripper.right_digit.image",
        "observation.images.overview",
    ];
    for key in keys {
        assert_eq!(
            peers::field(&read, &format!("video {key}")),
            format!("frames {frames} codec h264 pix_fmt yuv420p"),
        );
        let (lowest, own, next) = matched(&read, key);
        assert!(lowest >= 35.0, "{key}: {read}");
        // Each frame is its own tick's image: the next tick's matches it less well (the
        // camera sees the arm move; a tactile image changes little, but never matches better).
        assert!(own >= next, "{key}: {read}");
        if key.ends_with("overview") {
            assert!(own > next + 2.0, "{key}: {read}");
        }
    }
    for feature in [
        "observation.state",
        "observation.environment_state",
        "action",
        "timestamp",
        "frame_index",
        "episode_index",
        "index",
        "task_index",
    ]
    .into_iter()
    .chain(keys)
    {
        assert!(
            read.lines().any(|l| l == format!("stats {feature} ok")),
            "{feature}: {read}"
        );
    }

    // The state and the action are named as the components name their actuation (the
    // model's joints), the environment state as the model names its bodies.
    let info: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dataset.join("meta/info.json")).unwrap())
            .unwrap();
    let features = &info["features"];
    assert_eq!(
        features["observation.state"]["names"],
        features["action"]["names"]
    );
    let actions = features["action"]["names"].as_array().unwrap();
    assert!(
        actions.contains(&"arm/gripper/position".into()),
        "{actions:?}"
    );
    assert!(actions.contains(&"arm/wrist_3".into()), "{actions:?}");
    assert_eq!(info["robot_type"], "digit_world");
    // The last frame: the medium block rests on the target (0.42, 0.38), where the behaviour
    // put it, and the gripper was last told to open (position 0).
    let environment = "end 0 observation.environment_state";
    let (x, y) = (
        frame(&read, environment, "medium/block/x"),
        frame(&read, environment, "medium/block/y"),
    );
    assert!(
        (x - 0.42).hypot(y - 0.38) < 0.01,
        "the block ends at {x}, {y}"
    );
    assert_eq!(frame(&read, "end 0 action", "arm/gripper/position"), 0.0);
}

/// From `lerobot_read.py`'s `start I FEATURE …` or `end I FEATURE …` line (`which`), the value
/// of the element `name`.
fn frame(read: &str, which: &str, name: &str) -> f64 {
    let element = format!(" {name}=");
    let line = read
        .lines()
        .find(|l| l.starts_with(&format!("{which} ")) && l.contains(&element))
        .unwrap_or_else(|| panic!("no {which} {name}: {read}"));
    let (_, value) = line.split_once(&element).unwrap();
    value.split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn demonstrations_start_where_the_seed_puts_the_block_and_end_with_it_on_the_target() {
    let folder = tempfile::tempdir().unwrap();
    let demonstrate = |dataset: &str, seed: u64, episodes: u64| {
        let run = yarok(
            folder.path(),
            &[
                "run",
                "digit_world",
                "--behaviour",
                "demonstrate",
                "--dataset",
                dataset,
                "--set",
                &format!("behaviour/episodes={episodes}"),
                "--set",
                &format!("behaviour/seed={seed}"),
                "--set",
                "plugins/dataset/fps=20",
            ],
        );
        assert_succeeded(&run);
        let path = folder.path().join(dataset);
        (
            peers::run("lerobot_read.py", &[path.to_str().unwrap()]),
            path,
        )
    };
    let (read, first) = demonstrate("first", 7, 2);
    assert_eq!(totals(&read)[0], 2, "{read}");
    let starts: Vec<[f64; 2]> = (0..2)
        .map(|episode| {
            let which = format!("start {episode} observation.environment_state");
            let start = [
                frame(&read, &which, "medium/block/x"),
                frame(&read, &which, "medium/block/y"),
            ];
            // Within the drawn region, not where the world's template puts the block.
            assert!((0.56..=0.68).contains(&start[0]), "{start:?}");
            assert!((-0.12..=0.06).contains(&start[1]), "{start:?}");
            assert!((start[0] - 0.62).hypot(start[1] - 0.02) > 1e-3, "{start:?}");
            let which = format!("end {episode} observation.environment_state");
            let end = [
                frame(&read, &which, "medium/block/x"),
                frame(&read, &which, "medium/block/y"),
            ];
            assert!((end[0] - 0.42).hypot(end[1] - 0.38) < 0.005, "{end:?}");
            start
        })
        .collect();
    assert_ne!(starts[0], starts[1]);
    // The same seed, the same frames, bit for bit; another seed, other starts.
    let (_, again) = demonstrate("again", 7, 2);
    let data = "data/chunk-000/file-000.parquet";
    assert_eq!(
        std::fs::read(first.join(data)).unwrap(),
        std::fs::read(again.join(data)).unwrap()
    );
    let (other, _) = demonstrate("other", 8, 1);
    assert_ne!(
        frame(
            &other,
            "start 0 observation.environment_state",
            "medium/block/x"
        ),
        starts[0][0]
    );
}

#[test]
fn each_shard_of_a_run_of_episodes_is_a_dataset_of_its_episodes() {
    let folder = tempfile::tempdir().unwrap();
    for shard in ["0/2", "1/2"] {
        let run = yarok(
            folder.path(),
            &[
                "run",
                "tactile_rig_world",
                "--behaviour",
                "collect",
                "--shard",
                shard,
                "--dataset",
                "presses",
                "--record",
                "run.mcap",
                "--set",
                "behaviour/out=\"samples\"",
                "--set",
                "behaviour/points=2",
                "--set",
                "plugins/dataset/fps=100",
                "--set",
                "plugins/mcap/image_hz=100.0",
            ],
        );
        assert_succeeded(&run);
    }
    // 2 × 2 points at 3 depths: presses 0, 2, … are shard 0's, 1, 3, … shard 1's; each an
    // episode of its shard's dataset, matched with the episode's own recording.
    for (index, numbers) in [(0, [0, 2, 4, 6, 8, 10]), (1, [1, 3, 5, 7, 9, 11])] {
        let dataset = folder.path().join(format!("presses_{index}_of_2"));
        let recordings: Vec<String> = numbers
            .iter()
            .map(|n| {
                let path = folder.path().join(format!("run_episode_{n:04}.mcap"));
                path.to_str().unwrap().to_owned()
            })
            .collect();
        let mut args = vec![dataset.to_str().unwrap()];
        args.extend(recordings.iter().map(String::as_str));
        let read = peers::run("lerobot_read.py", &args);
        assert_eq!(totals(&read)[0], 6, "shard {index}: {read}");
        for episode in 0..6 {
            let line = peers::field(&read, &format!("episode {episode}"));
            assert!(line.ends_with("tasks tactile_rig_world"), "{read}");
        }
        let key = "observation.images.sensor.image";
        let (lowest, _, _) = matched(&read, key);
        assert!(lowest >= 35.0, "shard {index}: {read}");
    }
}

#[test]
fn a_folder_holding_other_files_is_not_overwritten() {
    let folder = tempfile::tempdir().unwrap();
    let precious = folder.path().join("notes/thesis.tex");
    std::fs::create_dir_all(precious.parent().unwrap()).unwrap();
    std::fs::write(&precious, "chapter 1").unwrap();
    let run = yarok(folder.path(), &["run", "digit_world", "--dataset", "notes"]);
    assert!(!run.status.success());
    let said = String::from_utf8_lossy(&run.stderr);
    assert_says(&said, &["notes holds files but no dataset"]);
    assert_eq!(std::fs::read_to_string(&precious).unwrap(), "chapter 1");
}

/// `yarok run tactile_rig_world --dataset DATASET` in `folder` (quick: one press).
fn presses(folder: &Path, dataset: &str) -> Output {
    yarok(
        folder,
        &[
            "run",
            "tactile_rig_world",
            "--dataset",
            dataset,
            "--set",
            "behaviour/out=\"samples\"",
        ],
    )
}

#[test]
fn a_dataset_is_replaced_whole_by_the_next_run_and_a_users_file_in_it_is_never_removed() {
    let folder = tempfile::tempdir().unwrap();
    assert_succeeded(&presses(folder.path(), "presses"));
    assert_succeeded(&presses(folder.path(), "presses"));
    let dataset = folder.path().join("presses");
    let read = peers::run("lerobot_read.py", &[dataset.to_str().unwrap()]);
    assert_eq!(totals(&read)[0], 1, "{read}");
    // Written beside, moved into place: nothing of the run is left beside the folder.
    let beside: Vec<String> = std::fs::read_dir(folder.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with('.'))
        .collect();
    assert!(beside.is_empty(), "{beside:?}");

    // A file of the user's inside the dataset: the folder is no longer yarok's to replace.
    let labels = dataset.join("meta/my_labels.csv");
    std::fs::write(&labels, "episode,label\n0,good\n").unwrap();
    let before = std::fs::read(dataset.join("data/chunk-000/file-000.parquet")).unwrap();
    let run = presses(folder.path(), "presses");
    assert!(!run.status.success());
    assert_says(
        String::from_utf8_lossy(&run.stderr),
        &["presses holds a dataset yarok wrote, and files it did not (meta/my_labels.csv)"],
    );
    assert_eq!(
        std::fs::read_to_string(&labels).unwrap(),
        "episode,label\n0,good\n"
    );
    assert_eq!(
        std::fs::read(dataset.join("data/chunk-000/file-000.parquet")).unwrap(),
        before
    );
}

#[test]
fn folders_that_are_not_yaroks_datasets_are_refused_and_left_byte_for_byte() {
    let folder = tempfile::tempdir().unwrap();
    let mine = folder.path().join("data/mine.csv");
    std::fs::create_dir_all(mine.parent().unwrap()).unwrap();
    std::fs::write(&mine, "1,2,3\n").unwrap();
    // The working folder itself.
    for empty in ["", "."] {
        let run = presses(folder.path(), empty);
        assert!(!run.status.success(), "{empty:?}");
        assert_says(
            String::from_utf8_lossy(&run.stderr),
            &["is no folder of its own"],
        );
    }
    // Anything with a meta/info.json is not yarok's for that.
    let garbage = folder.path().join("garbage");
    std::fs::create_dir_all(garbage.join("meta")).unwrap();
    std::fs::write(garbage.join("meta/info.json"), "garbage").unwrap();
    let run = presses(folder.path(), "garbage");
    assert_says(
        String::from_utf8_lossy(&run.stderr),
        &["garbage holds files but no dataset yarok wrote"],
    );
    let older = folder.path().join("older");
    std::fs::create_dir_all(older.join("meta")).unwrap();
    std::fs::write(
        older.join("meta/info.json"),
        r#"{"codebase_version": "v2.1", "fps": 30}"#,
    )
    .unwrap();
    let run = presses(folder.path(), "older");
    assert_says(
        String::from_utf8_lossy(&run.stderr),
        &["older holds a LeRobot dataset (v2.1) that yarok did not write"],
    );
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "1,2,3\n");
    assert_eq!(
        std::fs::read_to_string(garbage.join("meta/info.json")).unwrap(),
        "garbage"
    );
    assert!(
        std::fs::read_to_string(older.join("meta/info.json"))
            .unwrap()
            .contains("v2.1")
    );
    let names: Vec<String> = std::fs::read_dir(folder.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.starts_with('.')), "{names:?}");
}

#[test]
fn a_second_run_into_a_folder_being_written_is_refused() {
    let folder = tempfile::tempdir().unwrap();
    let mut first = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .current_dir(folder.path())
        .args(["run", "digit_world", "--dataset", "shared", "--set"])
        .arg("behaviour/out=\"shots\"")
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let lock = folder.path().join(".shared.yarok-lock");
    let started = std::time::Instant::now();
    while !lock.exists() {
        assert!(
            started.elapsed().as_secs() < 120,
            "the first run never took the folder"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let second = presses(folder.path(), "shared");
    assert!(!second.status.success());
    assert_says(
        String::from_utf8_lossy(&second.stderr),
        &[&format!(
            "another yarok run (process {}) is writing a dataset into shared",
            first.id()
        )],
    );
    assert!(first.wait().unwrap().success());
    let read = peers::run(
        "lerobot_read.py",
        &[folder.path().join("shared").to_str().unwrap()],
    );
    assert_eq!(totals(&read)[0], 1, "{read}");
    assert!(!lock.exists());
}
