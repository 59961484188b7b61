//! The `yarok` command line.
//!
//! ```text
//! yarok --help
//! yarok compose WORLD [--set [/PATH/]KEY=VALUE]... [--out FILE]
//! yarok tactile digit|gelsight|geltip DEPTH OUT.png [--background PNG] [--geltip-params DIR]
//!               [--noise SIGMA] [--seed N]
//! ```
//!
//! `compose` writes the composed MJCF of WORLD — a bundled component's tag (e.g.
//! `tumble-tower`) or an MJCF template file, in which bundled components' tags may be used — to
//! standard output or FILE. `--set` overrides a config value of the world (`rows=4`) or of the
//! component at a path (`/tower/rows=4`).
//!
//! `tactile` turns a depth map into a tactile image with a sensor's optical model. DEPTH is a
//! 16-bit PNG in millimetres or a `.npy`/`.npy.gz` float array in the model's unit (DIGIT: the raw
//! z-buffer, as the reference; a PNG selects DIGIT's metric mode). GelTip needs its geometry:
//! `--geltip-params DIR` with `bkg_depth_m.npy.gz` and `light_field_{0,1,2}.npy.gz`.

use std::path::PathBuf;
use std::process::ExitCode;

use yarok::components::catalogue;
use yarok::core::component::Declaration;
use yarok::core::compose::{compose_configured, compose_declaration};
use yarok::core::config::{RunConfig, Settings};

const USAGE: &str = "usage: yarok compose WORLD [--set [/PATH/]KEY=VALUE]... [--out FILE]
       yarok tactile digit|gelsight|geltip DEPTH OUT.png [--background PNG] [--noise SIGMA] [--seed N]
                     [--geltip-params DIR] [--light-fields files|linear|plane]
  WORLD  a bundled component tag, or an MJCF template file
  DEPTH  a 16-bit PNG in millimetres, or a .npy/.npy.gz float array
  DIR    GelTip geometry: bkg_depth_m.npy.gz (the membrane's depth) and, for --light-fields files
         (the default), light_field_{0,1,2}.npy.gz; linear and plane compute the fields for three
         LEDs on a 12.6 mm ring at the membrane's nearest depth";

struct Args {
    world: String,
    settings: Settings,
    out: Option<PathBuf>,
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "-h" || a == "--help") {
        println!("{USAGE}");
        return ExitCode::SUCCESS;
    }
    let result = match args.first().map(String::as_str) {
        Some("tactile") => tactile::run(&args[1..]),
        _ => parse(args.into_iter()).and_then(run),
    };
    match result {
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

fn run(args: Args) -> Result<(), String> {
    let bundled = catalogue();
    let composition = match bundled.iter().find(|c| c.declaration().tag() == args.world) {
        Some(component) => compose_configured(*component, &args.settings),
        None if PathBuf::from(&args.world).is_file() => {
            let world = bundled.iter().fold(
                Declaration::new("world").template_file(&args.world),
                |d, c| d.uses_type(*c),
            );
            compose_declaration(world, &args.settings)
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

mod tactile {
    use yarok::components::tactile::geltip::{GelTipModel, GelTipParams, read_membrane};
    use yarok::components::tactile::light_fields::{LightFieldMethod, led_ring};
    use yarok::components::tactile::phong::{PhongModel, PhongParams};
    use yarok::components::tactile::{default_background, npy};

    struct Options<'a> {
        sensor: &'a str,
        depth: &'a str,
        out: &'a str,
        background: Option<&'a str>,
        geltip_params: Option<&'a str>,
        light_fields: Option<LightFieldMethod>,
        noise: Option<f64>,
        seed: u64,
    }

    fn options(args: &[String]) -> Result<Options<'_>, String> {
        let [sensor, depth, out, rest @ ..] = args else {
            return Err(super::USAGE.to_owned());
        };
        let mut options = Options {
            sensor,
            depth,
            out,
            background: None,
            geltip_params: None,
            light_fields: None,
            noise: None,
            seed: 0,
        };
        let mut rest = rest.iter();
        while let Some(flag) = rest.next() {
            let value = rest.next().ok_or_else(|| format!("{flag} needs a value"))?;
            match flag.as_str() {
                "--background" => options.background = Some(value),
                "--geltip-params" => options.geltip_params = Some(value),
                "--light-fields" => {
                    options.light_fields = match value.as_str() {
                        "files" => None,
                        "linear" => Some(LightFieldMethod::Linear),
                        "plane" => Some(LightFieldMethod::Plane),
                        other => {
                            return Err(format!(
                                "--light-fields {other}: expected files, linear or plane"
                            ));
                        }
                    }
                }
                "--noise" => {
                    options.noise = Some(
                        value
                            .parse()
                            .map_err(|_| format!("--noise {value}: not a number"))?,
                    )
                }
                "--seed" => {
                    options.seed = value
                        .parse()
                        .map_err(|_| format!("--seed {value}: not an integer"))?
                }
                other => return Err(format!("unknown option {other}\n{}", super::USAGE)),
            }
        }
        Ok(options)
    }

    /// The depth map and its width; PNGs are millimetres, converted to metres.
    fn depth(path: &str) -> Result<(Vec<f32>, usize, bool), String> {
        if path.ends_with(".png") {
            let image = image::open(path)
                .map_err(|e| format!("{path}: {e}"))?
                .to_luma16();
            let width = image.width() as usize;
            return Ok((
                image.pixels().map(|p| f32::from(p[0]) / 1000.0).collect(),
                width,
                true,
            ));
        }
        let array = npy::read(path).map_err(|e| e.to_string())?;
        match array.shape[..] {
            [_, width] => Ok((array.data, width, false)),
            _ => Err(format!(
                "{path}: expected a 2-D array, got shape {:?}",
                array.shape
            )),
        }
    }

    /// The GelTip model of the geometry in `dir`, its light fields read from there or computed.
    fn geltip(dir: &str, method: Option<LightFieldMethod>) -> Result<GelTipModel, String> {
        let params = GelTipParams::default();
        let Some(method) = method else {
            return GelTipModel::load(params, dir).map_err(|e| e.to_string());
        };
        let (membrane, width) = read_membrane(dir).map_err(|e| e.to_string())?;
        let nearest = membrane.iter().copied().fold(f32::INFINITY, f32::min);
        let leds = led_ring(params.lights.len(), 0.0126, f64::from(nearest));
        GelTipModel::from_geometry(params, &membrane, width, &leds, method)
            .map_err(|e| format!("{dir}: {e}"))
    }

    pub(super) fn run(args: &[String]) -> Result<(), String> {
        let options = options(args)?;
        let (depth, width, metric) = depth(options.depth)?;
        let height = depth.len() / width.max(1);
        let background = match options.background {
            Some(path) => {
                let image = image::open(path)
                    .map_err(|e| format!("{path}: {e}"))?
                    .to_rgb8();
                if (image.width() as usize, image.height() as usize) != (width, height) {
                    return Err(format!(
                        "{path} is {}×{}, the depth map {width}×{height}",
                        image.width(),
                        image.height()
                    ));
                }
                image.into_raw()
            }
            None => default_background(width, height),
        };
        let image = match options.sensor {
            "digit" | "gelsight" => {
                let mut params = match (options.sensor, metric) {
                    ("digit", true) => PhongParams::digit_metric(),
                    ("digit", false) => PhongParams::digit(),
                    _ => PhongParams::gelsight2014(),
                };
                params.texture_sigma = options.noise.unwrap_or(params.texture_sigma);
                params.seed = options.seed;
                PhongModel::new(params)
                    .render(&depth, width, &background)
                    .map_err(|e| format!("{}: {e}", options.depth))?
            }
            "geltip" => {
                let dir = options
                    .geltip_params
                    .ok_or("geltip needs --geltip-params DIR")?;
                let mut model = geltip(dir, options.light_fields)?;
                if model.size() != (width, height) {
                    let (w, h) = model.size();
                    return Err(format!(
                        "the GelTip geometry is {h}×{w}, the depth map {height}×{width}"
                    ));
                }
                model
                    .render(&depth, &background)
                    .map_err(|e| format!("{}: {e}", options.depth))?
            }
            other => {
                return Err(format!(
                    "unknown sensor {other:?}: digit, gelsight or geltip"
                ));
            }
        };
        image::RgbImage::from_raw(width as u32, height as u32, image)
            .ok_or("internal: image size")?
            .save(options.out)
            .map_err(|e| format!("{}: {e}", options.out))
    }
}
