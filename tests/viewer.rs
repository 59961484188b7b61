//! The viewer and the inspector (feature `viewer`) under Xvfb, driven from outside by a
//! third-party X client (python-xlib, a separate process) as a user would: the viewer's window
//! shows the scene (the table's and the arm's colours), the space bar pauses it (platform time
//! stops) and resumes it, a drag orbits the camera and Tab switches to the model's camera, and
//! closing the window ends the run cleanly; Backspace puts the world back under a behaviour in
//! motion, which ends saying its motion was stopped; kept open, the window shows the world as the
//! behaviour left it until it is closed; the inspector's window
//! shows the DIGITs' images and, under them, the arm's and gripper's named states as text that
//! Tesseract OCR (a separate process) reads back; without an X server the viewer fails saying so, or runs on when
//! asked to.
#![cfg(feature = "viewer")]

use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use yarok_test::assert_says;
use yarok_test::{XServer, peers};

/// An X server of the test's own, with the third-party X client that drives its windows.
struct Xvfb(XServer);

impl Xvfb {
    fn start() -> Self {
        Self(XServer::start())
    }

    /// Runs `x11_window.py` on this display for the window titled `title…`.
    fn window(&self, title: &str, command: &[&str]) -> String {
        let mut args = vec![self.0.display(), title];
        args.extend(command);
        peers::run("x11_window.py", &args)
    }

    /// `yarok ARGS` on this display.
    fn yarok(&self, args: &[&str]) -> Child {
        Command::new(env!("CARGO_BIN_EXE_yarok"))
            .args(args)
            .env("DISPLAY", self.0.display())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    }
}

/// The platform time in a viewer's title (`yarok - t = 1.23 s`), and whether it is paused.
fn title_time(title: &str) -> (f64, bool) {
    let time = title
        .split("t = ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no time in the title {title:?}"));
    (time, title.contains("paused"))
}

/// Waits for `child` to exit, at most `within`; its status and standard error.
fn finished(mut child: Child, within: Duration) -> (std::process::ExitStatus, String) {
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            let output = child.wait_with_output().unwrap();
            return (status, String::from_utf8_lossy(&output.stderr).into_owned());
        }
        if started.elapsed() > within {
            let _ = child.kill();
            panic!("still running after {within:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn the_viewer_shows_the_scene_pauses_on_a_key_and_ends_the_run_when_closed() {
    let x = Xvfb::start();
    let run = x.yarok(&["run", "pick_and_place_world", "--viewer"]);
    x.window("yarok - t", &["wait", "60"]);
    std::thread::sleep(Duration::from_millis(500));

    let folder = tempfile::tempdir().unwrap();
    let shot = folder.path().join("viewer.png");
    let size = x.window("yarok - t", &["screenshot", shot.to_str().unwrap()]);
    assert_eq!(size.trim(), "size 800 600");
    let image = image::open(&shot).unwrap().to_rgb8();
    let share = |matches: fn(&image::Rgb<u8>) -> bool| {
        image.pixels().filter(|p| matches(p)).count() as f64 / f64::from(800 * 600)
    };
    // The table's wood, lit, and the arm's blue caps.
    let table = share(|p| p[0] > 150 && (100..170).contains(&p[1]) && p[2] < 120);
    let arm = share(|p| p[2] > 170 && p[0] < 120 && p[1] > 80);
    assert!(table > 0.02, "table pixels {table}");
    assert!(arm > 0.001, "arm pixels {arm}");

    x.window("yarok - t", &["key", "space"]);
    std::thread::sleep(Duration::from_millis(300));
    let (paused_at, paused) = title_time(&x.window("yarok - t", &["title"]));
    assert!(paused, "the title says paused");
    std::thread::sleep(Duration::from_secs(1));
    let (later, _) = title_time(&x.window("yarok - t", &["title"]));
    assert_eq!(later, paused_at, "platform time stands still while paused");
    // Paused, the scene changes only as the camera does: a left drag orbits it, Tab shows the
    // model's first camera (the world's overview).
    let shoot = |name: &str| {
        std::thread::sleep(Duration::from_millis(300));
        let path = folder.path().join(name);
        x.window("yarok - t", &["screenshot", path.to_str().unwrap()]);
        image::open(&path).unwrap().to_rgb8().into_raw()
    };
    let still = shoot("still.png");
    assert!(shoot("again.png") == still, "a paused scene stays still");
    x.window("yarok - t", &["drag", "1", "400", "300", "550", "300"]);
    let orbited = shoot("orbited.png");
    assert!(orbited != still, "the drag orbits the camera");
    x.window("yarok - t", &["key", "Tab"]);
    assert!(shoot("overview.png") != orbited, "Tab shows another camera");
    let (still_at, _) = title_time(&x.window("yarok - t", &["title"]));
    assert_eq!(still_at, paused_at, "still paused");

    x.window("yarok - t", &["key", "space"]);
    std::thread::sleep(Duration::from_millis(500));
    let (resumed, paused) = title_time(&x.window("yarok - t", &["title"]));
    assert!(
        !paused && resumed > paused_at,
        "{resumed} after {paused_at}"
    );

    x.window("yarok - t", &["close"]);
    let (status, stderr) = finished(run, Duration::from_secs(10));
    assert!(status.success(), "{status}: {stderr}");
}

#[test]
fn the_inspector_shows_the_probes_images_and_the_named_states() {
    let x = Xvfb::start();
    let folder = tempfile::tempdir().unwrap();
    let out = format!("behaviour/out={:?}", folder.path().display().to_string());
    let run = x.yarok(&["run", "digit_world", "--inspect", "--set", &out]);
    x.window("yarok inspector", &["wait", "60"]);
    std::thread::sleep(Duration::from_millis(500));
    let shot = folder.path().join("inspector.png");
    let size = x.window("yarok inspector", &["screenshot", shot.to_str().unwrap()]);
    // Four images (each DIGIT's tactile image and depth, 240×320, under their labels) side by
    // side, 348 pixels high; the named states' rows under them.
    let (width, height) = size
        .trim()
        .strip_prefix("size ")
        .unwrap()
        .split_once(' ')
        .unwrap();
    assert_eq!(width, "980");
    assert!(height.parse::<u32>().unwrap() > 348 + 6 * 10, "{size}");
    let image = image::open(&shot).unwrap().to_rgb8();
    // The tactile images' gel, under their labels: the colours of the real DIGIT's untouched gel
    // that the bundled calibration draws.
    let colour = |p: &image::Rgb<u8>| p.0.map(|c| c / 8);
    let real_gel: std::collections::HashSet<[u8; 3]> =
        yarok::components::tactile::calibration::Calibration::digit()
            .background()
            .pixels()
            .map(colour)
            .collect();
    // Each half of the window holds one DIGIT's panes; wherever the run is when the shot is
    // taken, a press covers at most part of a gel.
    for (half, xs) in [("left", 0..490), ("right", 490..980)] {
        let gel = image
            .enumerate_pixels()
            .filter(|(x, _, p)| xs.contains(x) && real_gel.contains(&colour(p)))
            .count();
        assert!(gel > 240 * 320 / 4, "{gel} gel pixels in the {half} half");
    }
    assert_shows_named_states(&peers::run("ocr.py", &[shot.to_str().unwrap(), "348"]));
    x.window("yarok inspector", &["close"]);
    let (status, stderr) = finished(run, Duration::from_secs(30));
    assert!(status.success(), "{status}: {stderr}");
}

/// `text`, read from the inspector's table, has the gripper's and the arm's states: each field
/// under its component's path and the state's name, with a value of its kind.
fn assert_shows_named_states(text: &str) {
    let value = |name: &str| {
        let line = text.lines().find(|line| line.contains(name));
        let line = line.unwrap_or_else(|| panic!("no `{name}` in:\n{text}"));
        line.split_once(name).unwrap().1.trim().to_owned()
    };
    for flag in ["gripper state moving", "gripper state object_detected"] {
        assert!(["true", "false"].contains(&value(flag).as_str()), "{text}");
    }
    let position: f64 = value("gripper state position").parse().expect(text);
    assert!((0.0..=255.0).contains(&position), "{text}");
    // q, qd and the TCP: six numbers each, to three decimals, in brackets.
    let vectors: Vec<&str> = text
        .lines()
        .filter(|line| line.contains("arm state"))
        .collect();
    assert_eq!(vectors.len(), 3, "{text}");
    for line in vectors {
        let numbers = line
            .split_once('[')
            .and_then(|(_, rest)| rest.strip_suffix(']'));
        let numbers: Vec<&str> = numbers.expect(text).split_whitespace().collect();
        assert_eq!(numbers.len(), 6, "{text}");
        for number in numbers {
            let decimals = number.split_once('.').map(|(_, decimals)| decimals.len());
            assert!(
                number.parse::<f64>().is_ok() && decimals == Some(3),
                "{text}"
            );
        }
    }
    assert!(value("arm state q").starts_with('['), "{text}");
    assert!(value("arm state qd").starts_with('['), "{text}");
}

#[test]
fn backspace_puts_the_world_back_under_a_behaviour_in_motion_which_ends_saying_so() {
    let x = Xvfb::start();
    let run = x.yarok(&["run", "pick_and_place_world", "--viewer"]);
    x.window("yarok - t", &["wait", "60"]);
    // 1.5 s in, the arm is on its way to the first block.
    let started = Instant::now();
    loop {
        let (time, _) = title_time(&x.window("yarok - t", &["title"]));
        if time >= 1.5 {
            break;
        }
        assert!(started.elapsed() < Duration::from_secs(60), "at {time} s");
        std::thread::sleep(Duration::from_millis(100));
    }
    x.window("yarok - t", &["key", "BackSpace"]);
    // As the README says: the behaviour is not restarted; its motion is stopped and the run
    // ends with that error.
    let (status, stderr) = finished(run, Duration::from_secs(30));
    assert!(!status.success(), "{stderr}");
    assert_says(&stderr, &["the motion was stopped"]);
}

#[test]
fn kept_open_the_viewer_shows_the_ended_world_until_it_is_closed() {
    let x = Xvfb::start();
    let mut run = x.yarok(&[
        "run",
        "digit_world",
        "--behaviour",
        "idle",
        "--viewer",
        "--set",
        "plugins/viewer/keep_open=true",
        "--set",
        "behaviour/seconds=0.5",
    ]);
    x.window("yarok - t", &["wait", "60"]);
    let started = Instant::now();
    let title = loop {
        let title = x.window("yarok - t", &["title"]);
        if title.contains("ended") {
            break title;
        }
        assert!(started.elapsed() < Duration::from_secs(60), "{title}");
        std::thread::sleep(Duration::from_millis(100));
    };
    let (ended_at, _) = title_time(&title);
    assert!((0.49..0.52).contains(&ended_at), "{title}");
    // Once the run has ended, the keys that would change it do nothing; the window stays.
    x.window("yarok - t", &["key", "space"]);
    x.window("yarok - t", &["key", "BackSpace"]);
    std::thread::sleep(Duration::from_secs(1));
    assert!(
        run.try_wait().unwrap().is_none(),
        "the run waits for the window"
    );
    let title = x.window("yarok - t", &["title"]);
    assert_eq!(title_time(&title), (ended_at, false), "{title}");
    assert_says(&title, &["ended"]);
    // The camera still moves, and S shows the cameras (the DIGITs' on the fingers among them)
    // with their frames.
    let folder = tempfile::tempdir().unwrap();
    let shoot = |name: &str| {
        std::thread::sleep(Duration::from_millis(300));
        let path = folder.path().join(name);
        x.window("yarok - t", &["screenshot", path.to_str().unwrap()]);
        image::open(&path).unwrap().to_rgb8()
    };
    let still = shoot("ended.png");
    x.window("yarok - t", &["key", "s"]);
    let cameras = shoot("cameras.png");
    let changed = still
        .pixels()
        .zip(cameras.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 200, "{changed} pixels changed by S");
    x.window("yarok - t", &["drag", "1", "400", "300", "550", "300"]);
    assert!(
        shoot("orbited.png") != cameras,
        "the drag orbits the camera"
    );

    x.window("yarok - t", &["close"]);
    let (status, stderr) = finished(run, Duration::from_secs(10));
    assert!(status.success(), "{status}: {stderr}");
}

#[test]
fn without_an_x_server_the_viewer_says_so_or_runs_on_when_asked() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "run",
            "empty_world",
            "--viewer",
            "--set",
            "behaviour/seconds=0.1",
        ];
        args.extend(extra);
        Command::new(env!("CARGO_BIN_EXE_yarok"))
            .args(&args)
            .env("DISPLAY", ":9999")
            .output()
            .unwrap()
    };
    let failed = run(&[]);
    let stderr = String::from_utf8_lossy(&failed.stderr);
    assert_eq!(failed.status.code(), Some(2), "{stderr}");
    assert_says(
        &stderr,
        &["viewer", "no window can open on display \":9999\""],
    );
    let headless = run(&["--set", "plugins/viewer/headless=true"]);
    assert!(
        headless.status.success(),
        "{}",
        String::from_utf8_lossy(&headless.stderr)
    );
}
