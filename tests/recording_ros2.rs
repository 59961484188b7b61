//! `yarok run digit_world --record FILE --profile ros2` read back by the two ROS 2 readers on
//! PyPI, each in a process of its own: `rosbags` (which refuses a file whose MCAP profile is not
//! `ros2`) and `mcap-ros2-support`. Both find every topic with its ROS 2 type and as many
//! messages as the run recorded; the joint positions equal, bit for bit, those the run's
//! `joints_csv` recorder wrote at the same ticks; the DIGITs' images decode (colour PNG, depth
//! `32FC1` in metres within the gel) and the behaviour's log lines read as it logged them.

use std::process::Command;

mod support;
use support::digit_world_recording;
use yarok_test::peers;

use digit_world_recording::{assert_gel_depths, record_digit_world};
use yarok_test::assert_says;

/// Lines of `output` that start with `name `, without it.
fn lines<'a>(output: &'a str, name: &str) -> Vec<&'a str> {
    let prefix = format!("{name} ");
    output
        .lines()
        .filter_map(|line| line.strip_prefix(prefix.as_str()))
        .collect()
}

fn count(output: &str, topic: &str, msgtype: &str) -> usize {
    let found = lines(output, "topic")
        .into_iter()
        .find_map(|line| line.strip_prefix(&format!("{topic} {msgtype} ")))
        .unwrap_or_else(|| panic!("no topic {topic} of type {msgtype} in\n{output}"));
    found.parse().unwrap()
}

#[test]
fn a_ros2_recording_reads_back_in_rosbags_and_mcap_ros2_support() {
    let folder = tempfile::tempdir().unwrap();
    let (mcap, csv) = record_digit_world(folder.path(), &["--profile", "ros2"]);
    let rows = &csv.rows;
    assert!(rows.len() > 250, "{} rows", rows.len());
    let duration = rows.last().unwrap()[0];

    for reader in ["rosbags", "mcap_ros2"] {
        let read = peers::run("ros2_bag_read.py", &[reader, mcap.to_str().unwrap()]);
        assert_eq!(peers::field(&read, "profile"), "ros2", "{reader}");
        for (topic, msgtype) in [
            ("/joint_states", "sensor_msgs/msg/JointState"),
            ("/tf", "tf2_msgs/msg/TFMessage"),
            ("/clock", "rosgraph_msgs/msg/Clock"),
        ] {
            assert_eq!(
                count(&read, topic, msgtype),
                rows.len(),
                "{reader}: {topic}"
            );
        }
        assert_eq!(
            lines(&read, "clock").len(),
            rows.len(),
            "{reader}: a clock message each time the state is recorded"
        );

        // Joint positions: the CSV's every 10th tick, column for column, bit for bit.
        let names: Vec<&str> = peers::field(&read, "joint_names").split(' ').collect();
        csv.assert_positions(&names, &lines(&read, "joint_state"), reader);
        let transforms = peers::field(&read, "transforms");
        assert!(transforms.ends_with(" world"), "{reader}: {transforms}");

        // The DIGITs: colour PNGs and depth in metres, ten a second, at the same times.
        for side in ["left", "right"] {
            let image_topic = format!("/arm/gripper/{side}_digit/image");
            let depth_topic = format!("/arm/gripper/{side}_digit/depth");
            if reader == "mcap_ros2" {
                // 32FC1 counts metres, and the channel says so.
                assert!(
                    lines(&read, "channel_metadata")
                        .contains(&format!("{depth_topic} depth_unit_m=1e0").as_str()),
                    "{read}"
                );
            }
            let images = count(&read, &image_topic, "sensor_msgs/msg/CompressedImage");
            assert_eq!(
                count(&read, &depth_topic, "sensor_msgs/msg/Image"),
                images,
                "{reader}"
            );
            assert!(
                images as f64 >= duration * 10.0 - 1.0,
                "{reader}: {images} images"
            );
            for image in lines(&read, "image")
                .into_iter()
                .filter_map(|line| line.strip_prefix(&format!("{image_topic} ")))
            {
                let fields: Vec<&str> = image.split(' ').collect();
                assert_eq!(fields[1..4], ["240", "320", "RGB"], "{reader}: {image}");
                assert!(fields[4].parse::<u32>().unwrap() > 20, "{reader}: {image}");
            }
            let depths: Vec<(f64, f64)> = lines(&read, "depth")
                .into_iter()
                .filter_map(|line| line.strip_prefix(&format!("{depth_topic} ")))
                .map(|depth| {
                    let fields: Vec<&str> = depth.split(' ').collect();
                    assert_eq!(fields[1..3], ["240", "320"], "{reader}: {depth}");
                    (fields[3].parse().unwrap(), fields[4].parse().unwrap())
                })
                .collect();
            assert_eq!(depths.len(), images, "{reader}");
            assert_gel_depths(&depths, reader);
        }

        let logs = lines(&read, "log");
        assert_eq!(logs.len(), 3, "{reader}: {logs:?}");
        assert!(
            logs[2].ends_with("the block is on the target") && logs[2].contains(" 20 t = "),
            "{reader}: {logs:?}"
        );
    }
}

#[test]
fn a_profile_without_a_recording_is_refused() {
    let output = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .args(["run", "digit_world", "--profile", "ros2"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_says(&stderr, &["give --record FILE.mcap too"]);
}

#[test]
fn an_unknown_profile_names_the_ones_there_are() {
    let folder = tempfile::tempdir().unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_yarok"))
        .current_dir(folder.path())
        .args([
            "run",
            "empty_world",
            "--record",
            "run.mcap",
            "--profile",
            "ros1",
        ])
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains(
            "plugin mcap failed: `profile`: no recording profile \"ros1\": there are \"foxglove\" \
             and \"ros2\""
        ),
        "{stderr}"
    );
}
