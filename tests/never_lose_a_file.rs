//! yarok's writers never lose a byte of a file they did not write: random folder trees (the
//! user's files, partial and foreign datasets, links to files and folders, read-only entries)
//! are given as the output of `yarok run --dataset`, `--record`, `--video` and `yarok tactile
//! calibrate`, and every file and link that was there before is there after, unchanged, whether
//! the run wrote its output or refused it. A run into a new path succeeds, and so does a second
//! run into what the first wrote (yarok replaces what it wrote), so refusing everything would
//! fail the test. No run panics or hangs.
#![cfg(feature = "dataset")]

use std::collections::BTreeMap;
use std::os::unix::fs::{PermissionsExt, symlink};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use yarok_test::generator::Generator;

mod support;
use support::yarok_binary::quick_calibrate;

/// Runs per writer.
const CASES: usize = 24;

/// The longest a run may take before it counts as a hang.
const BOUND: Duration = Duration::from_secs(120);

/// A writer under test: the arguments that write `target`.
#[derive(Debug, Clone, Copy)]
enum Writer {
    Dataset,
    Record,
    Video,
    Calibrate,
}

impl Writer {
    fn args(self, target: &str) -> Vec<String> {
        let run = |world: &str, option: &str| {
            let args = [
                "run",
                world,
                "--behaviour",
                "idle",
                "--set",
                "behaviour/seconds=0.1",
            ];
            args.into_iter()
                .chain([option, target])
                .map(str::to_owned)
                .collect()
        };
        match self {
            Self::Dataset => run("pick_and_place_world", "--dataset"),
            Self::Record => run("tower_world", "--record"),
            Self::Video => run("pick_and_place_world", "--video"),
            Self::Calibrate => quick_calibrate("press/background.png", "press/presses.csv", target),
        }
    }

    /// An output path that holds nothing yet.
    fn fresh(self) -> &'static str {
        match self {
            Self::Dataset => "fresh_dataset",
            Self::Record => "fresh.mcap",
            Self::Video => "fresh.mp4",
            Self::Calibrate => "fresh.json",
        }
    }
}

/// What a folder tree holds, by path: a file's bytes and mode, or a link's target.
#[derive(Debug, PartialEq)]
enum Entry {
    File(Vec<u8>, u32),
    Link(PathBuf),
    Folder,
}

fn snapshot(root: &Path) -> BTreeMap<PathBuf, Entry> {
    let mut entries = BTreeMap::new();
    let mut folders = vec![root.to_owned()];
    while let Some(folder) = folders.pop() {
        for item in std::fs::read_dir(&folder).unwrap() {
            let path = item.unwrap().path();
            let metadata = std::fs::symlink_metadata(&path).unwrap();
            let entry = if metadata.is_symlink() {
                Entry::Link(std::fs::read_link(&path).unwrap())
            } else if metadata.is_dir() {
                folders.push(path.clone());
                Entry::Folder
            } else {
                Entry::File(std::fs::read(&path).unwrap(), metadata.permissions().mode())
            };
            entries.insert(path.strip_prefix(root).unwrap().to_owned(), entry);
        }
    }
    entries
}

/// A random tree of a user's files in `root`, with the calibration's inputs under `press/`;
/// the paths a writer could be given.
fn plant(root: &Path, generator: &mut Generator) -> Vec<String> {
    let real =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("yarok-components/data/tactile-real/digit");
    std::fs::create_dir_all(root.join("press/frames")).unwrap();
    std::fs::copy(
        real.join("background.png"),
        root.join("press/background.png"),
    )
    .unwrap();
    let presses = std::fs::read_to_string(real.join("presses.csv")).unwrap();
    let presses: Vec<&str> = presses.lines().take(4).collect();
    std::fs::write(root.join("press/presses.csv"), presses.join("\n") + "\n").unwrap();
    for press in &presses[1..] {
        let frame = format!("{}.png", press.split(',').next().unwrap());
        std::fs::copy(
            real.join("frames").join(&frame),
            root.join("press/frames").join(frame),
        )
        .unwrap();
    }

    let folder_names = [
        "a", "a/b", "data", "meta", "videos", "ds", "ds/meta", "ds/data",
    ];
    let file_names = [
        "notes.txt",
        "mine.csv",
        "clip.mp4",
        "run.mcap",
        "out.json",
        "frame.png",
        "info.json",
        "holiday.mp4",
        "labels.csv",
        "fresh.mp4",
        "fresh.mcap",
        "fresh.json",
    ];
    let mut folders = vec![String::new()];
    for _ in 0..generator.below(5) {
        let folder = generator.pick(&folder_names).to_owned();
        std::fs::create_dir_all(root.join(&folder)).unwrap();
        folders.push(folder);
    }
    let mut paths: Vec<String> = folders.iter().filter(|f| !f.is_empty()).cloned().collect();
    for _ in 0..2 + generator.below(8) {
        let folder = &folders[generator.below(folders.len())];
        let path = Path::new(folder).join(generator.pick(&file_names));
        if root.join(&path).is_dir() {
            continue;
        }
        let length = generator.below(3000);
        std::fs::write(root.join(&path), generator.bytes(length)).unwrap();
        if generator.below(4) == 0 {
            std::fs::set_permissions(root.join(&path), std::fs::Permissions::from_mode(0o444))
                .unwrap();
        }
        paths.push(path.to_string_lossy().into_owned());
    }
    // A dataset's skeleton: garbage, or a LeRobot dataset's info yarok did not write.
    if generator.below(2) == 0 {
        let folder = generator.pick(&["ds", "a/ds", "lerobot"]);
        std::fs::create_dir_all(root.join(folder).join("meta")).unwrap();
        let info = generator.pick(&["garbage", r#"{"codebase_version": "v2.1", "fps": 30}"#]);
        std::fs::write(root.join(folder).join("meta/info.json"), info).unwrap();
        paths.push(folder.to_owned());
    }
    // Links to what is there (a file, a folder) and to nothing.
    for _ in 0..generator.below(3) {
        let to = paths
            .get(generator.below(paths.len() + 1))
            .map_or_else(|| PathBuf::from("nowhere"), |p| root.join(p));
        let link = root.join(format!("link{}", generator.below(1000)));
        if !link.exists() && std::fs::symlink_metadata(&link).is_err() {
            symlink(&to, &link).unwrap();
            paths.push(link.file_name().unwrap().to_string_lossy().into_owned());
        }
    }
    if generator.below(4) == 0
        && let Some(folder) = folders.iter().rfind(|f| !f.is_empty())
    {
        std::fs::set_permissions(root.join(folder), std::fs::Permissions::from_mode(0o555))
            .unwrap();
    }
    // A third of the runs write a new path in one of the folders.
    if generator.below(3) == 0 {
        let folder = &folders[generator.below(folders.len())];
        return vec![
            Path::new(folder)
                .join("new.out")
                .to_string_lossy()
                .into_owned(),
        ];
    }
    paths.extend(
        [
            ".",
            "",
            "press",
            "press/presses.csv",
            "press/background.png",
        ]
        .map(String::from),
    );
    paths.push(root.to_string_lossy().into_owned());
    paths
}

/// Runs `yarok ARGS` in `folder` with `folder` as home; its exit code and standard error.
fn yarok_in(folder: &Path, args: &[String]) -> (i32, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(args)
        .current_dir(folder)
        .env("HOME", folder)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > BOUND {
            let _ = child.kill();
            panic!("yarok {args:?} still ran after {BOUND:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    let code = status
        .code()
        .unwrap_or_else(|| panic!("yarok {args:?} was killed ({status}): {stderr}"));
    (code, stderr)
}

#[test]
fn random_folder_trees_lose_no_byte_of_a_users_file() {
    let mut generator = Generator(0x5eed_f11e);
    for writer in [
        Writer::Dataset,
        Writer::Record,
        Writer::Video,
        Writer::Calibrate,
    ] {
        let (mut written, mut refused) = (0, 0);
        for case in 0..CASES {
            let tree = tempfile::tempdir().unwrap();
            let root = tree.path();
            let paths = plant(root, &mut generator);
            let target = paths[generator.below(paths.len())].clone();
            let before = snapshot(root);
            let args = writer.args(&target);
            let (code, stderr) = yarok_in(root, &args);
            assert!(
                code == 0 || (code == 2 && stderr.starts_with("error: ")),
                "case {case}: yarok {args:?} exited {code}: {stderr}"
            );
            let after = snapshot(root);
            for (path, entry) in &before {
                assert_eq!(
                    after.get(path),
                    Some(entry),
                    "case {case}: yarok {args:?} (exit {code}: {stderr}) changed {}",
                    path.display()
                );
            }
            if code == 0 {
                written += 1;
            } else {
                refused += 1;
            }

            // A path that holds nothing is written, and written again over what yarok wrote.
            if case == 0 {
                let fresh = format!("new/{}", writer.fresh());
                for time in ["first", "second"] {
                    let (code, stderr) = yarok_in(root, &writer.args(&fresh));
                    assert_eq!(code, 0, "{time} run into {fresh}: {stderr}");
                }
            }
            make_removable(root);
        }
        eprintln!("{writer:?}: {written} runs wrote their output, {refused} were refused");
        assert!(
            refused > 0 && written > 0,
            "{writer:?}: {written} written, {refused} refused"
        );
    }
}

/// Gives every folder under `root` back its owner's write permission, so the tree can go.
fn make_removable(root: &Path) {
    for (path, entry) in snapshot(root) {
        if entry == Entry::Folder {
            std::fs::set_permissions(root.join(path), std::fs::Permissions::from_mode(0o755))
                .unwrap();
        }
    }
}

/// The arguments of a short run writing the dataset `ds`.
fn dataset_run() -> Vec<String> {
    Writer::Dataset.args("ds")
}

/// A shared dataset tampered with (`tamper` given the folder holding `ds`): the next run into
/// it is refused with an error saying `said`, and every file is as it was.
fn refused_after(tamper: impl FnOnce(&Path), said: &str) {
    let tree = tempfile::tempdir().unwrap();
    let root = tree.path();
    let (code, stderr) = yarok_in(root, &dataset_run());
    assert_eq!(code, 0, "{stderr}");
    tamper(root);
    let before = snapshot(root);
    let (code, stderr) = yarok_in(root, &dataset_run());
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains(said), "{stderr}");
    assert_eq!(snapshot(root), before, "{stderr}");
}

/// Adds `entry` to the manifest of the dataset `ds` in `root`.
fn list_in_manifest(root: &Path, entry: &str) {
    let manifest = root.join("ds/meta/yarok_files.json");
    let mut files: Vec<String> =
        serde_json::from_str(&std::fs::read_to_string(&manifest).unwrap()).unwrap();
    files.push(entry.to_owned());
    std::fs::write(&manifest, serde_json::to_string(&files).unwrap()).unwrap();
}

#[test]
fn a_manifest_naming_files_outside_its_dataset_is_refused_and_removes_nothing() {
    refused_after(
        |root| {
            std::fs::write(root.join("beside.txt"), "a user's notes").unwrap();
            list_in_manifest(root, "../beside.txt");
        },
        "lists \"../beside.txt\", which is not a path inside the dataset",
    );
    refused_after(
        |root| {
            std::fs::write(root.join("abs.txt"), "a user's notes").unwrap();
            list_in_manifest(root, &root.join("abs.txt").display().to_string());
        },
        "which is not a path inside the dataset",
    );
    refused_after(
        |root| {
            std::fs::create_dir(root.join("documents")).unwrap();
            std::fs::write(root.join("documents/thesis.tex"), "a user's thesis").unwrap();
            symlink(root.join("documents"), root.join("ds/docs")).unwrap();
            list_in_manifest(root, "docs/thesis.tex");
            list_in_manifest(root, "docs");
        },
        "which goes through a link out of the dataset",
    );
}

#[test]
fn a_lock_or_partial_name_held_by_a_users_file_folder_or_link_is_refused_never_removed() {
    refused_after(
        |root| {
            std::fs::create_dir(root.join(".ssh")).unwrap();
            std::fs::write(root.join(".ssh/id_rsa"), "a user's key").unwrap();
            symlink(root.join(".ssh/id_rsa"), root.join(".ds.yarok-lock")).unwrap();
        },
        ".ds.yarok-lock is in the way of the lock of",
    );
    refused_after(
        |root| std::fs::write(root.join(".ds.yarok-lock"), "a user's file").unwrap(),
        ".ds.yarok-lock is in the way of the lock of",
    );
    refused_after(
        |root| {
            std::fs::create_dir(root.join(".ds.yarok-partial")).unwrap();
            std::fs::write(root.join(".ds.yarok-partial/work.txt"), "a user's work").unwrap();
        },
        ".ds.yarok-partial is in the way of the dataset being written",
    );
}

/// A killed run's leftovers (its lock, with a process id that has ended, and its partial
/// dataset, marked) are recognised and cleared by the next run, which writes the dataset.
#[test]
fn a_killed_runs_lock_and_partial_dataset_are_taken_over() {
    let tree = tempfile::tempdir().unwrap();
    let root = tree.path();
    let ended = Command::new("true").spawn().unwrap();
    let pid = ended.id();
    let _ = { ended }.wait();
    std::fs::write(root.join(".ds.yarok-lock"), pid.to_string()).unwrap();
    std::fs::create_dir(root.join(".ds.yarok-partial")).unwrap();
    std::fs::write(
        root.join(".ds.yarok-partial/.yarok-partial"),
        pid.to_string(),
    )
    .unwrap();
    let (code, stderr) = yarok_in(root, &dataset_run());
    assert_eq!(code, 0, "{stderr}");
    assert!(root.join("ds/meta/info.json").is_file());
    assert!(!root.join(".ds.yarok-lock").exists());
    assert!(!root.join(".ds.yarok-partial").exists());
    assert!(!root.join("ds/.yarok-partial").exists());
}

/// A link to a user's file planted at, and taken from, an output's path over and over while runs
/// write it: the user's file is never written through, whatever the timing. Each run writes its
/// recording or is refused naming the path; none succeeds with the recording written through
/// the link.
#[test]
fn a_link_swapped_in_while_a_run_writes_never_redirects_the_write() {
    let folder = tempfile::tempdir().unwrap();
    let root = folder.path();
    let users = root.join("users_notes.txt");
    std::fs::write(&users, "a user's notes").unwrap();
    let output = root.join("swapped.mcap");
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let swapper = {
        let (stop, output, users) = (stop.clone(), output.clone(), users.clone());
        std::thread::spawn(move || {
            let mut swaps = 0u64;
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                let link = output.with_file_name(format!(".swap{swaps}"));
                if symlink(&users, &link).is_ok() {
                    // Atomically in place of whatever is at the output's path, then away.
                    let _ = std::fs::rename(&link, &output);
                    std::thread::sleep(Duration::from_micros(300));
                    if std::fs::symlink_metadata(&output).is_ok_and(|m| m.file_type().is_symlink())
                    {
                        let _ = std::fs::remove_file(&output);
                    }
                }
                swaps += 1;
                std::thread::sleep(Duration::from_micros(200));
            }
            swaps
        })
    };
    let mut written = 0;
    for _ in 0..12 {
        let (code, said) = yarok_in(root, &Writer::Record.args("swapped.mcap"));
        if code == 0 {
            written += 1;
        } else {
            assert!(said.contains("swapped.mcap"), "{said}");
        }
        assert_eq!(std::fs::read(&users).unwrap(), b"a user's notes", "{said}");
    }
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    let swaps = swapper.join().unwrap();
    assert!(swaps > 100, "the link was swapped {swaps} times");
    assert_eq!(std::fs::read(&users).unwrap(), b"a user's notes");
    eprintln!("{written} of 12 runs wrote their recording; the link was swapped {swaps} times");
}
