//! `yarok run`: a bundled world with one of its demo behaviours.

use std::io::IsTerminal;

use yarok::RuntimeError;
use yarok::components::demos::{self, Demo};
use yarok::components::plugins::StatusLine;
use yarok::core::suggest::did_you_mean;

use super::{Failure, USAGE};

/// The options `yarok run` reads itself; the platform reads `--env`, `--set` and `--config`.
const OWN_OPTIONS: [&str; 7] = [
    "--behaviour",
    "--record",
    "--profile",
    "--dataset",
    "--video",
    "--viewer",
    "--inspect",
];
const PLATFORM_OPTIONS: [&str; 3] = ["--env", "--set", "--config"];

/// What to run.
#[derive(Debug, Default)]
struct Args {
    world: Option<String>,
    behaviour: Option<String>,
    /// The settings `--record`, `--dataset`, `--video`, `--viewer`, `--inspect`, `--shard` and `--bridge` stand for, as `--set`
    /// arguments: before the user's, which may refine them.
    plugins: Vec<String>,
    /// For the platform: `--env`, `--set` and `--config` with their values.
    platform: Vec<String>,
    list: bool,
    /// `--record`'s file was given.
    recording: bool,
    /// `--profile`'s value.
    profile: Option<String>,
}

fn parse(args: &[String]) -> Result<Args, String> {
    let mut parsed = Args::default();
    let mut args = args.iter();
    while let Some(arg) = args.next() {
        let mut value = || {
            args.next()
                .cloned()
                .ok_or_else(|| format!("{arg} needs a value"))
        };
        match arg.as_str() {
            "--list" => parsed.list = true,
            "--behaviour" => parsed.behaviour = Some(value()?),
            "--record" => {
                parsed.recording = true;
                parsed.set(&format!("plugins/mcap/path={:?}", value()?));
            }
            "--profile" => parsed.profile = Some(value()?),
            "--video" => parsed.set(&format!("plugins/video/path={:?}", value()?)),
            "--dataset" => parsed.set(&dataset(&value()?)?),
            "--shard" => parsed.set(&format!("platform/shard={:?}", value()?)),
            "--bridge" => parsed.set(&bridge()?),
            "--viewer" => parsed.set(&windows("viewer", "paused=false")?),
            "--inspect" => parsed.set(&windows("inspector", "rate=5.0")?),
            option if PLATFORM_OPTIONS.contains(&option) => {
                let value = value()?;
                parsed.platform.extend([arg.clone(), value]);
            }
            option if option.starts_with('-') => {
                let known = OWN_OPTIONS.iter().chain(&PLATFORM_OPTIONS).copied();
                return Err(format!(
                    "unknown option {option}{}\n{USAGE}",
                    did_you_mean(option, known.chain(["--list"]))
                ));
            }
            _ if parsed.world.is_none() => parsed.world = Some(arg.clone()),
            _ => return Err(format!("unexpected argument {arg:?}\n{USAGE}")),
        }
    }
    if let Some(profile) = parsed.profile.take() {
        if !parsed.recording {
            return Err(format!(
                "--profile {profile} says how --record records: give --record FILE.mcap too\n{USAGE}"
            ));
        }
        parsed.set(&format!("plugins/mcap/profile={profile:?}"));
    }
    Ok(parsed)
}

impl Args {
    fn set(&mut self, assignment: &str) {
        self.plugins
            .extend(["--set".to_owned(), assignment.to_owned()]);
    }
}

/// The setting that records a LeRobot dataset in `folder`, if this `yarok` can.
fn dataset(folder: &str) -> Result<String, String> {
    if cfg!(feature = "dataset") {
        Ok(format!("plugins/dataset/path={folder:?}"))
    } else {
        Err(
            "this yarok was built without the dataset recorder: build it with the `dataset` \
             feature (cargo run --release --features dataset --bin yarok -- run …)"
                .into(),
        )
    }
}

/// The setting that creates the Zenoh bridge, if this `yarok` has it.
fn bridge() -> Result<String, String> {
    if cfg!(feature = "zenoh") {
        Ok("plugins/zenoh/hz=50.0".into())
    } else {
        Err(
            "this yarok was built without the Zenoh bridge: build it with the `zenoh` feature \
             (cargo run --release --features zenoh --bin yarok -- run …)"
                .into(),
        )
    }
}

/// The setting that creates window plugin `plugin` (`key=value`, its default), if this
/// `yarok` has windows.
fn windows(plugin: &str, default: &str) -> Result<String, String> {
    if cfg!(feature = "viewer") {
        Ok(format!("plugins/{plugin}/{default}"))
    } else {
        Err(format!(
            "this yarok was built without windows: build it with the `viewer` feature \
             (cargo run --release --features viewer --bin yarok -- run …) to use the {plugin}"
        ))
    }
}

/// The bundled worlds and their behaviours, a line each.
fn list() -> String {
    demos::demos()
        .iter()
        .map(|demo| {
            let names: Vec<&str> = demo.behaviours.iter().map(|b| b.name).collect();
            format!("{:<22} {}", demo.tag(), names.join(", "))
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn find(world: &str) -> Result<Demo, String> {
    demos::find(world).ok_or_else(|| {
        let tags: Vec<String> = demos::demos().iter().map(Demo::tag).collect();
        format!(
            "no bundled world {world:?}{} (yarok run --list shows them)",
            did_you_mean(world, tags.iter().map(String::as_str))
        )
    })
}

/// Runs `yarok run` with the arguments after `run`.
pub(super) fn run(args: &[String]) -> Result<(), Failure> {
    let args = parse(args)?;
    if args.list {
        return super::print(&format!("{}\n", list())).map_err(Failure::from);
    }
    let world = args.world.ok_or_else(|| USAGE.to_owned())?;
    let demo = find(&world)?;
    let behaviour = demo.behaviour(args.behaviour.as_deref()).ok_or_else(|| {
        let names = demo.behaviours.iter().map(|b| b.name);
        format!(
            "{world} has no behaviour {:?}{}",
            args.behaviour.as_deref().unwrap_or_default(),
            did_you_mean(args.behaviour.as_deref().unwrap_or_default(), names)
        )
    })?;
    let mut platform = behaviour
        .install(yarok::platform().world_type(demo.world))
        .args(args.plugins.into_iter().chain(args.platform))
        .map_err(|e| e.to_string())?;
    if std::io::stderr().is_terminal() {
        platform = platform.plugin(StatusLine::new());
    }
    platform.run().map_err(|error| match &error {
        RuntimeError::Interrupted { signal } => Failure {
            message: error.to_string(),
            status: u8::try_from(128 + signal).unwrap_or(1),
        },
        error => Failure::from(error.to_string()),
    })
}
