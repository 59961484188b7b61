//! Many worlds per process and runs split into shards: worlds run in parallel, each with its
//! own seed and config, give what they give run one after another; the shards of a collection
//! run with `yarok run --shard I/N` write, between them, exactly the files the whole run writes.

use yarok::components::worlds::{Press, TactileRigWorld};
use yarok::core::runtime::run_parallel;

use yarok_test::peers;
mod support;
use support::yarok_binary;

use yarok_binary::{yarok, yarok_fails};
use yarok_test::assert_says;

/// A DIGIT rig (its texture noise seeded by the platform) pressed `depth` metres deep: the
/// tactile image's bytes.
fn press(seed: u64, depth: f64) -> Result<Vec<u8>, String> {
    let image = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    let kept = std::rc::Rc::clone(&image);
    yarok::platform()
        .world::<TactileRigWorld>()
        .set("sensor=\"digit\"")
        .and_then(|b| b.set("parallel=false"))
        .and_then(|b| b.set(&format!("platform/seed={seed}")))
        .map_err(|e| e.to_string())?
        .behaviour(move |pl| async move {
            let rig: TactileRigWorld = pl.get("/")?;
            let sample = rig
                .press(Press {
                    at: [0.0, 0.0],
                    depth,
                })
                .await?;
            *kept.borrow_mut() = sample.image.into_raw();
            Ok(())
        })
        .run()
        .map_err(|e| e.to_string())?;
    Ok(image.take())
}

#[test]
fn worlds_in_parallel_give_what_they_give_one_after_another() {
    let worlds = [(0, 0.0005), (1, 0.0005), (0, 0.001), (1, 0.001)];
    let jobs = || -> Vec<_> {
        worlds
            .iter()
            .map(|&(seed, depth)| move || press(seed, depth))
            .collect()
    };
    let parallel: Vec<Vec<u8>> = run_parallel(jobs(), 2)
        .into_iter()
        .collect::<Result<_, _>>()
        .unwrap();
    let sequential: Vec<Vec<u8>> = run_parallel(jobs(), 1)
        .into_iter()
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(parallel.len(), 4);
    for (index, (a, b)) in parallel.iter().zip(&sequential).enumerate() {
        assert!(a == b, "world {index} differs between the runs");
    }
    assert!(parallel[0] != parallel[1], "another seed, other noise");
    assert!(parallel[0] != parallel[2], "another depth, another image");
}

#[test]
fn the_shards_of_a_collection_are_the_whole_collection() {
    let folder = tempfile::tempdir().unwrap();
    let collect = |name: &str, shard: Option<&str>| {
        let out = folder.path().join(name);
        let out_setting = format!("behaviour/out={:?}", out.display().to_string());
        let recording = out.join("rig.mcap").display().to_string();
        let mut args = vec![
            "run",
            "tactile_rig_world",
            "--behaviour",
            "collect",
            "--record",
            &recording,
            "--set",
            "plugins/mcap/every=2",
            "--set",
            "plugins/mcap/image_hz=100",
            "--set",
            "sensor=\"digit\"",
            "--set",
            "behaviour/points=2",
            "--set",
            "behaviour/depths_mm=[0.5, 1.0]",
            "--set",
            &out_setting,
        ];
        args.extend(shard.map(|s| ["--shard", s]).into_iter().flatten());
        let (code, _, stderr) = yarok(&args);
        assert_eq!(code, 0, "{stderr}");
        out
    };
    let whole = collect("whole", None);
    let shards = [
        collect("shards", Some("0/3")),
        collect("shards", Some("1/3")),
        collect("shards", Some("2/3")),
    ];
    let index = std::fs::read_to_string(whole.join("index.csv")).unwrap();
    let mut rows: Vec<&str> = index.lines().collect();
    let header = rows.remove(0);
    assert_eq!(rows.len(), 2 * 2 * 2);
    let mut sharded = Vec::new();
    for (i, shard) in shards.iter().enumerate() {
        let part = std::fs::read_to_string(shard.join(format!("index_{i}_of_3.csv"))).unwrap();
        let mut lines = part.lines();
        assert_eq!(lines.next(), Some(header));
        sharded.extend(lines.map(str::to_owned));
    }
    sharded.sort_by_key(|row| row.split(',').next().unwrap().parse::<usize>().unwrap());
    assert_eq!(sharded, rows, "the shards' rows are the whole run's");
    let mut episodes = 0;
    for entry in std::fs::read_dir(&whole).unwrap() {
        let name = entry.unwrap().file_name();
        if name == "index.csv" || name == "rig.mcap" {
            continue;
        }
        let a = std::fs::read(whole.join(&name)).unwrap();
        let b = std::fs::read(shards[0].join(&name)).unwrap();
        assert!(a == b, "{name:?} differs");
        if name.to_string_lossy().starts_with("rig_episode_") {
            episodes += 1;
            let summary = peers::run("mcap_summary.py", &[whole.join(&name).to_str().unwrap()]);
            for topic in ["/joint_states", "/tf", "/sensor/image"] {
                assert!(
                    summary.contains(&format!("topic {topic} ")),
                    "{name:?} records {topic}:\n{summary}"
                );
            }
            assert_says(&summary, &["\njoint_state "]);
        }
    }
    assert_eq!(episodes, rows.len(), "one recording per press");
    for i in 0..3 {
        let run = shards[0].join(format!("rig_{i}_of_3.mcap"));
        assert!(run.exists(), "shard {i}'s own recording, named apart");
    }
    yarok_fails(
        &["run", "empty_world", "--shard", "3/3"],
        2,
        &["\"3/3\": expected I/N with 0 ≤ I < N"],
    );
}
