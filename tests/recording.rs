//! The recorders on the `pick_and_place` example. Its MCAP file read back by a third-party
//! reader (PyPI's `mcap`, images decoded by Pillow) in a separate process: the messages per
//! topic, the joint positions equal to those the run's `joints_csv` recorder wrote at the same
//! ticks, the camera's images decodable and not blank, and the behaviour's log lines. Its video
//! read back by `ffprobe`: every frame decodes, as many as the run's length at its rate.

use std::process::Command;

mod support;
use support::example_binary;
use support::joints_csv;
use yarok_test::peers;

use example_binary::example_binary;
use joints_csv::JointsCsv;

#[test]
fn a_pick_and_place_recording_reads_back_in_others_tools() {
    let folder = tempfile::tempdir().unwrap();
    let mcap = folder.path().join("run.mcap");
    let csv = folder.path().join("joints.csv");
    let video = folder.path().join("run.mp4");
    let quoted = |path: &std::path::Path| format!("\"{}\"", path.display());
    let output = Command::new(example_binary("pick_and_place"))
        .args(
            [
                format!("plugins/mcap/path={}", quoted(&mcap)),
                "plugins/mcap/cameras=[\"overview\"]".into(),
                "plugins/mcap/size=[160, 120]".into(),
                "plugins/mcap/image_hz=2".into(),
                format!("plugins/joints_csv/path={}", quoted(&csv)),
                "plugins/joints_csv/every=10".into(),
                format!("plugins/video/path={}", quoted(&video)),
                "plugins/video/size=[160, 120]".into(),
                "plugins/video/fps=10".into(),
            ]
            .iter()
            .flat_map(|setting| ["--set".to_owned(), setting.clone()]),
        )
        .output()
        .unwrap();
    yarok_test::assert_succeeded(&output);
    let summary = peers::run("mcap_summary.py", &[mcap.to_str().unwrap()]);
    let count = |topic: &str| -> usize {
        let line = summary
            .lines()
            .find(|l| l.starts_with(&format!("topic {topic} ")))
            .unwrap_or_else(|| panic!("no topic {topic} in\n{summary}"));
        line.rsplit(' ').next().unwrap().parse().unwrap()
    };

    // Joint positions: the CSV's every 10th tick, column for column.
    let csv = JointsCsv::read(&csv);
    let rows = &csv.rows;
    assert!(rows.len() > 1000, "{} rows", rows.len());
    assert_eq!(count("/joint_states"), rows.len());
    assert_eq!(count("/tf"), rows.len());
    let names: Vec<&str> = peers::field(&summary, "joint_names").split(' ').collect();
    let states: Vec<&str> = summary
        .lines()
        .filter_map(|l| l.strip_prefix("joint_state "))
        .collect();
    csv.assert_positions(&names, &states, "mcap");
    let frames: Vec<&str> = peers::field(&summary, "transforms").split(' ').collect();
    let count_of_frames: usize = frames[0].parse().unwrap();
    assert!(count_of_frames > 20, "{frames:?}");
    assert!(frames.contains(&"overview/optical"), "{frames:?}");

    // The run it is of.
    let metadata = peers::field(&summary, "metadata");
    assert!(
        metadata.starts_with("yarok environment=sim seed=")
            && metadata.contains(" timestep=0.002 ")
            && metadata.contains(" world=pick_and_place_world ")
            && metadata.ends_with(&format!("yarok={}", env!("CARGO_PKG_VERSION"))),
        "{metadata}"
    );

    // The camera: every half second of the run, decodable, not blank.
    let duration = rows.last().unwrap()[0];
    let images: Vec<&str> = summary
        .lines()
        .filter(|l| l.starts_with("image /cameras/overview "))
        .collect();
    assert_eq!(images.len(), count("/cameras/overview"));
    assert!(
        images.len() as f64 >= duration * 2.0 - 1.0,
        "{} images in {duration} s",
        images.len()
    );
    for image in &images {
        let fields: Vec<&str> = image.split(' ').collect();
        assert_eq!(fields[3..6], ["160", "120", "RGB"], "{image}");
        assert_eq!(fields[7], "overview/optical", "the camera's frame: {image}");
        let spread: u32 = fields[6].parse().unwrap();
        assert!(spread > 50, "a blank image: {image}");
    }

    // The behaviour's log lines, at the platform time they were logged.
    let logs: Vec<&str> = summary.lines().filter(|l| l.starts_with("log ")).collect();
    assert_eq!(logs.len(), 3 + 3, "{logs:?}");
    assert!(logs[0].ends_with("/large stacked"), "{logs:?}");
    assert!(logs[5].starts_with("log ") && logs[5].ends_with("mm from its place"));
    let stacked_at: f64 = logs[0].split(' ').nth(1).unwrap().parse().unwrap();
    assert!(stacked_at > 1.0 && stacked_at < duration, "{stacked_at}");

    // The video: every frame decodes; 10 a second of the run.
    let probe = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args([
            "-show_entries",
            "stream=nb_read_frames,width,height,codec_name",
        ])
        .args(["-of", "default=nw=1"])
        .arg(&video)
        .output()
        .unwrap();
    let probed = String::from_utf8_lossy(&probe.stdout);
    assert!(probe.status.success(), "{probed}");
    let value = |key: &str| {
        probed
            .lines()
            .find_map(|line| line.strip_prefix(&format!("{key}=")))
            .unwrap_or_else(|| panic!("no {key} in {probed}"))
            .to_owned()
    };
    assert_eq!(
        [value("codec_name"), value("width"), value("height")],
        ["h264", "160", "120"]
    );
    let frames: f64 = value("nb_read_frames").parse().unwrap();
    assert!(
        (frames - duration * 10.0).abs() <= 2.0,
        "{frames} frames in {duration} s"
    );
}
