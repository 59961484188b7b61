//! The `yarok` command line.
//!
//! ```text
//! yarok compose WORLD [--set [/PATH/]KEY=VALUE]... [--out FILE]
//! ```
//!
//! `compose` writes the composed MJCF of WORLD — a bundled component's tag (e.g.
//! `tumble-tower`) or an MJCF template file, in which bundled components' tags may be used — to
//! standard output or FILE. `--set` overrides a config value of the world (`rows=4`) or of the
//! component at a path (`/tower/rows=4`).

use std::path::PathBuf;
use std::process::ExitCode;

use yarok::components::catalogue;
use yarok::core::compose::{Declaration, Overrides, Value, compose_declaration, compose_with};

const USAGE: &str = "usage: yarok compose WORLD [--set [/PATH/]KEY=VALUE]... [--out FILE]
  WORLD  a bundled component tag, or an MJCF template file";

struct Args {
    world: String,
    overrides: Overrides,
    out: Option<PathBuf>,
}

fn main() -> ExitCode {
    match parse(std::env::args().skip(1)).and_then(run) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

fn parse(mut args: impl Iterator<Item = String>) -> Result<Args, String> {
    if args.next().as_deref() != Some("compose") {
        return Err(USAGE.to_owned());
    }
    let mut world = None;
    let mut overrides = Overrides::new();
    let mut out = None;
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--set" => {
                let assignment = args.next().ok_or("--set needs KEY=VALUE")?;
                let (target, value) = assignment
                    .split_once('=')
                    .ok_or(format!("--set {assignment}: expected KEY=VALUE"))?;
                let (path, key) = match target.rsplit_once('/') {
                    Some(("", key)) => ("/".to_owned(), key),
                    Some((path, key)) => (path.to_owned(), key),
                    None => ("/".to_owned(), target),
                };
                overrides
                    .entry(path)
                    .or_default()
                    .set(key, Value::String(value.to_owned()));
            }
            "--out" => out = Some(PathBuf::from(args.next().ok_or("--out needs a file")?)),
            "-h" | "--help" => return Err(USAGE.to_owned()),
            _ if world.is_none() => world = Some(arg),
            _ => return Err(format!("unexpected argument {arg:?}\n{USAGE}")),
        }
    }
    Ok(Args {
        world: world.ok_or(USAGE)?,
        overrides,
        out,
    })
}

fn run(args: Args) -> Result<(), String> {
    let bundled = catalogue();
    let composition = match bundled.iter().find(|c| c.declaration().tag() == args.world) {
        Some(component) => compose_with(*component, &args.overrides),
        None if PathBuf::from(&args.world).is_file() => {
            let world = bundled.iter().fold(
                Declaration::new("world").template_file(&args.world),
                |d, c| d.uses_type(*c),
            );
            compose_declaration(world, &args.overrides)
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
        Some(path) => {
            std::fs::write(&path, xml).map_err(|e| format!("cannot write {}: {e}", path.display()))
        }
        None => {
            print!("{xml}");
            Ok(())
        }
    }
}
