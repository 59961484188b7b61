//! `yarok run digit_world --record FILE` (the `foxglove` profile) checked as Foxglove's tools
//! take it, in a process of its own (`scripts/peers/foxglove_validate.py`): every channel's
//! schema is free of `$ref` and follows the field rules of the open-source Foxglove Studio's and
//! Lichtblick's JSON Schema parser; every message validates (PyPI's `jsonschema`) against its
//! channel's schema and against Foxglove's published schema of that name (npm's
//! `@foxglove/schemas`); the chunks are zstd-compressed; depth is `foxglove.RawImage` `16UC1`
//! in micrometres (numpy reads it back). The joints are named as the model
//! names them, the images are in the cameras' optical frames that `/tf` carries, and the joint
//! positions (read by PyPI's `mcap`) are, bit for bit, those of the run's `joints_csv` file.

mod support;
use support::digit_world_recording;
use yarok_test::peers;

use digit_world_recording::{assert_gel_depths, record_digit_world};

#[test]
fn a_foxglove_recording_validates_against_foxglove_schemas() {
    let folder = tempfile::tempdir().unwrap();
    let (mcap, csv) = record_digit_world(folder.path(), &[]);
    let schemas = peers::foxglove_schemas();
    let checked = peers::run(
        "foxglove_validate.py",
        &[mcap.to_str().unwrap(), schemas.to_str().unwrap()],
    );

    let rows = csv.rows.len();
    let mut expected = vec![
        (
            "/joint_states".to_owned(),
            "foxglove.JointStates",
            Some(rows),
        ),
        ("/tf".to_owned(), "foxglove.FrameTransforms", Some(rows)),
        ("/log".to_owned(), "foxglove.Log", Some(3)),
    ];
    for side in ["left", "right"] {
        for (probe, schema) in [
            ("image", "foxglove.CompressedImage"),
            ("depth", "foxglove.RawImage"),
        ] {
            let topic = format!("/arm/gripper/{side}_digit/{probe}");
            expected.push((topic, schema, None));
        }
    }
    for (topic, schema, count) in expected {
        let line = checked
            .lines()
            .find_map(|l| l.strip_prefix(&format!("channel {topic} {schema} ")))
            .unwrap_or_else(|| panic!("no channel {topic} {schema} in\n{checked}"));
        let found: usize = line.parse().unwrap();
        assert!(found > 0, "{topic}");
        if let Some(count) = count {
            assert_eq!(found, count, "{topic}");
        }
    }
    let chunks: Vec<&str> = peers::field(&checked, "chunks").split(' ').collect();
    assert_eq!(chunks[1..], ["zstd"], "every chunk compressed: {chunks:?}");
    assert!(chunks[0].parse::<usize>().unwrap() > 1, "{chunks:?}");

    // The images are in their cameras' optical frames, which /tf carries, as it does the block.
    let frames: Vec<&str> = peers::field(&checked, "frames").split(' ').collect();
    for side in ["left", "right"] {
        for probe in ["image", "depth"] {
            let frame = peers::field(
                &checked,
                &format!("image_frame /arm/gripper/{side}_digit/{probe}"),
            );
            assert_eq!(frame, format!("arm/gripper/{side}_digit/camera/optical"));
            assert!(frames.contains(&frame), "{frame} not in {frames:?}");
        }
    }
    assert!(frames.contains(&"large/block"), "{frames:?}");

    // Depth in micrometres, the gel's as it is.
    for side in ["left", "right"] {
        let topic = format!("/arm/gripper/{side}_digit/depth");
        let depths: Vec<(f64, f64)> = checked
            .lines()
            .filter_map(|l| l.strip_prefix(&format!("depth {topic} ")))
            .map(|depth| {
                let fields: Vec<&str> = depth.split(' ').collect();
                assert_eq!(
                    fields[..5],
                    ["16UC1", "240", "320", "480", "1e-06"],
                    "{depth}"
                );
                (fields[5].parse().unwrap(), fields[6].parse().unwrap())
            })
            .collect();
        assert_gel_depths(&depths, &topic);
    }

    // The joints by their names, positions bit for bit the CSV's.
    let summary = peers::run("mcap_summary.py", &[mcap.to_str().unwrap()]);
    let names: Vec<&str> = peers::field(&summary, "joint_names").split(' ').collect();
    assert_eq!(names[0], "arm/shoulder_pan");
    assert!(names.iter().all(|name| !name.contains('[')), "{names:?}");
    let states: Vec<&str> = summary
        .lines()
        .filter_map(|l| l.strip_prefix("joint_state "))
        .collect();
    csv.assert_positions(&names, &states, "mcap");
}
