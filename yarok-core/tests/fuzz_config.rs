//! Run configuration and recorder paths on generated input: any `--set` argument or TOML text
//! is read or refused with an error naming where it came from, never a panic, and its values
//! reach a platform's settings or an error; two recorders given one file, however the path is
//! spelt (`./`, `//`, `dir/../`, a link to the folder, folders not made yet), are refused
//! before the run, and two different files are not.

use std::path::{Path, PathBuf};

use proptest::prelude::*;
use yarok_core::BoxError;
use yarok_core::component::{Component, Declaration, Mock, MockBackend};
use yarok_core::config::RunConfig;
use yarok_core::runtime::{Platform, Plugin, World};

/// A `--set` argument: a target from the sections, paths and keys users write, then a value.
fn assignment() -> impl Strategy<Value = String> {
    let target = prop_oneof![
        Just("platform/".to_owned()),
        Just("behaviour/".to_owned()),
        Just("plugins/mcap/".to_owned()),
        Just("interfaces/arm/".to_owned()),
        Just("/arm/".to_owned()),
        Just(String::new()),
        "[a-z/_.\"]{0,12}",
    ];
    let key = prop_oneof![
        Just("realtime".to_owned()),
        Just("tick_hz".to_owned()),
        Just("seed".to_owned()),
        Just("model_cache".to_owned()),
        Just("shard".to_owned()),
        "[a-z_]{0,8}",
    ];
    let value = prop_oneof![
        Just("true".to_owned()),
        Just("\"yes\"".to_owned()),
        Just("1e308".to_owned()),
        Just("-0".to_owned()),
        Just("nan".to_owned()),
        Just("\"~/x\"".to_owned()),
        Just("\"\"".to_owned()),
        Just("\"3/2\"".to_owned()),
        Just("[1, \"a\"]".to_owned()),
        Just("{ a = 1 }".to_owned()),
        "[0-9]{1,25}",
        ".{0,16}",
    ];
    (target, key, prop::bool::ANY, value).prop_map(|(target, key, equals, value)| {
        format!("{target}{key}{}{value}", if equals { "=" } else { "" })
    })
}

/// TOML text made of section headers and assignments users write, and noise.
fn toml() -> impl Strategy<Value = String> {
    let line = prop_oneof![
        Just("[platform]".to_owned()),
        Just("[behaviour]".to_owned()),
        Just("[plugins.mcap]".to_owned()),
        Just("[components.\"/arm\"]".to_owned()),
        Just("[environments.real.components.\"/arm\"]".to_owned()),
        Just("environment = \"real\"".to_owned()),
        "[a-z_]{1,10} = [0-9a-z\"\\[\\]., ]{0,12}",
        ".{0,20}",
    ];
    prop::collection::vec(line, 0..8).prop_map(|lines| lines.join("\n"))
}

/// Every way the settings are read; none may panic.
fn read_all(config: &RunConfig) {
    let settings = config.settings("sim");
    let _ = settings.platform_settings();
    let _ = settings.plugin_settings::<std::collections::BTreeMap<String, toml::Value>>("mcap");
}

struct Empty;
impl Component for Empty {
    fn declaration() -> Declaration {
        Declaration::new("empty").template("<mujoco><worldbody/></mujoco>")
    }
}

/// A recorder that writes one file.
struct Recorder(&'static str, PathBuf);
impl Plugin for Recorder {
    fn name(&self) -> String {
        self.0.to_owned()
    }
    fn writes(&self) -> Vec<PathBuf> {
        vec![self.1.clone()]
    }
    fn step(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        Ok(())
    }
}

/// Whether a platform with recorders writing `first` and `second` is refused as writing one
/// file twice.
fn refused(first: &Path, second: &Path) -> bool {
    let built = Platform::builder()
        .world::<Empty>()
        .environment("mock")
        .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
        .plugin(Recorder("first", first.to_owned()))
        .plugin(Recorder("second", second.to_owned()))
        .build();
    match built {
        Ok(_) => false,
        Err(error) => {
            let message = error.to_string();
            assert!(message.contains("would both write"), "{message}");
            true
        }
    }
}

/// A spelling of `relative` (inside `root`): each folder as itself, `./` before it, a doubled
/// slash, or a detour through `existing/..`; the folder `existing` may be named by `link`, a
/// link to it.
fn spelt(root: &Path, relative: &[&str], ways: &[u8]) -> PathBuf {
    let mut text = root.display().to_string();
    for (part, way) in relative.iter().zip(ways.iter().cycle()) {
        let part = if *part == "existing" && way % 5 == 4 {
            "link"
        } else {
            part
        };
        text.push_str(match way % 5 {
            0 | 4 => "/",
            1 => "/./",
            2 => "//",
            _ => "/existing/../",
        });
        text.push_str(part);
    }
    PathBuf::from(text)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(5_000))]

    #[test]
    fn any_set_argument_is_read_or_refused_naming_it(arguments in prop::collection::vec(assignment(), 1..4)) {
        let mut config = RunConfig::default();
        for argument in &arguments {
            if let Err(error) = config.set(argument) {
                prop_assert!(error.origin.contains(argument.as_str()), "{error}");
            }
        }
        read_all(&config);
    }

    #[test]
    fn any_toml_is_read_or_refused_naming_its_file(text in toml()) {
        match RunConfig::from_toml(&text, "run.toml") {
            Ok(config) => read_all(&config),
            Err(error) => prop_assert!(error.origin.starts_with("run.toml"), "{error}"),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2_000))]

    #[test]
    fn one_file_however_spelt_has_one_writer(
        folders in prop::sample::select(vec![
            vec!["existing"], vec!["existing", "new"], vec!["new", "newer"], vec![],
        ]),
        first_ways in prop::collection::vec(0u8..5, 1..4),
        second_ways in prop::collection::vec(0u8..5, 1..4),
        other_name in prop::bool::ANY,
    ) {
        let root = tempfile::tempdir().unwrap();
        std::fs::create_dir(root.path().join("existing")).unwrap();
        std::os::unix::fs::symlink(root.path().join("existing"), root.path().join("link")).unwrap();
        let mut first = folders.clone();
        first.push("run.mcap");
        let mut second = folders.clone();
        second.push(if other_name { "other.mcap" } else { "run.mcap" });
        let first = spelt(root.path(), &first, &first_ways);
        let second = spelt(root.path(), &second, &second_ways);
        prop_assert_eq!(refused(&first, &second), !other_name, "{} and {}", first.display(), second.display());
    }
}
