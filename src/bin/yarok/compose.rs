//! `yarok compose`: the composed MJCF of a world.

use std::path::PathBuf;

use yarok::components::{catalogue, template_world};
use yarok::core::compose::{compose_configured, compose_declaration};
use yarok::core::config::{RunConfig, Settings};
use yarok::core::output_file::write_output;

use super::USAGE;

struct Args {
    world: String,
    settings: Settings,
    out: Option<PathBuf>,
}

fn parse(mut args: impl Iterator<Item = String>) -> Result<Args, String> {
    let mut world = None;
    let mut config = RunConfig::default();
    let mut out = None;
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--set" => {
                let assignment = args.next().ok_or("--set needs KEY=VALUE")?;
                config.set(&assignment).map_err(|e| e.to_string())?;
            }
            "--out" => out = Some(PathBuf::from(args.next().ok_or("--out needs a file")?)),
            _ if world.is_none() => world = Some(arg),
            _ => return Err(format!("unexpected argument {arg:?}\n{USAGE}")),
        }
    }
    Ok(Args {
        world: world.ok_or(USAGE)?,
        settings: config.settings("sim"),
        out,
    })
}

/// Runs `yarok compose` with the arguments after `compose`.
pub(super) fn run(args: &[String]) -> Result<(), String> {
    let args = parse(args.iter().cloned())?;
    let bundled = catalogue();
    let composition = match bundled.iter().find(|c| c.declaration().tag() == args.world) {
        Some(component) => compose_configured(*component, &args.settings),
        None if PathBuf::from(&args.world).is_file() => {
            compose_declaration(template_world(&args.world), &args.settings)
        }
        None => {
            let tags: Vec<String> = bundled
                .iter()
                .map(|c| c.declaration().tag().to_owned())
                .collect();
            return Err(format!(
                "{} is neither a bundled component ({}) nor a file",
                args.world,
                tags.join(", ")
            ));
        }
    }
    .map_err(|e| e.to_string())?;
    let xml = composition.to_xml();
    match args.out {
        Some(path) => write_output(
            &path,
            "composed world",
            composed_by_yarok,
            format!("{COMPOSED_MARK}\n{xml}").as_bytes(),
        )
        .map_err(|refused| refused.to_string()),
        None => super::print(&xml),
    }
}

/// The comment a world `compose --out` writes starts with: how an existing file is known as
/// yarok's (a user's template never is).
const COMPOSED_MARK: &str = "<!-- composed by yarok compose: regenerated, not edited -->";

/// Whether the file at `path` is a world `compose --out` wrote.
fn composed_by_yarok(path: &std::path::Path) -> std::io::Result<bool> {
    Ok(yarok::core::output::head(path, COMPOSED_MARK.len() as u64)?
        .starts_with(COMPOSED_MARK.as_bytes()))
}
