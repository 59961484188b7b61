//! `yarok tactile`: a depth map turned into a tactile image by a sensor's optical model.

use yarok::components::probe_images::depth_from_png;
use yarok::components::tactile::calibration::Calibration;
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
    /// A `.npy` map holds the reference DIGIT model's raw z-buffer values, not metres.
    zbuffer: bool,
    calibration: Option<&'a str>,
    pixels_per_mm: Option<f64>,
}

/// The sensors `yarok tactile` renders for.
const SENSORS: [&str; 3] = ["digit", "gelsight", "geltip"];

fn options(args: &[String]) -> Result<Options<'_>, String> {
    let [sensor, depth, out, rest @ ..] = args else {
        return Err(format!(
            "yarok tactile needs a sensor, a depth map and an output image\n{}",
            super::USAGE
        ));
    };
    if !SENSORS.contains(&sensor.as_str()) {
        return Err(format!(
            "unknown sensor {sensor:?}: {} (or calibrate)",
            SENSORS.join(", ")
        ));
    }
    let mut options = Options {
        sensor,
        depth,
        out,
        background: None,
        geltip_params: None,
        light_fields: None,
        noise: None,
        seed: 0,
        zbuffer: false,
        calibration: None,
        pixels_per_mm: None,
    };
    let mut rest = rest.iter();
    while let Some(flag) = rest.next() {
        let value = rest.next().ok_or_else(|| format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--background" => options.background = Some(value),
            "--depth-unit" => {
                options.zbuffer = match value.as_str() {
                    "m" => false,
                    "zbuffer" => true,
                    other => {
                        return Err(format!(
                            "--depth-unit {other}: expected m (metres) or zbuffer (the \
                             reference DIGIT model's raw values)"
                        ));
                    }
                }
            }
            "--calibration" => options.calibration = Some(value),
            "--pixels-per-mm" => {
                options.pixels_per_mm = Some(
                    value
                        .parse()
                        .ok()
                        .filter(|v: &f64| v.is_finite() && *v > 0.0)
                        .ok_or_else(|| format!("--pixels-per-mm {value}: not a positive number"))?,
                )
            }
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
                        .ok()
                        .filter(|sigma: &f64| (0.0..=MAX_NOISE).contains(sigma))
                        .ok_or_else(|| {
                            format!(
                                "--noise {value}: the gel's texture (metres), a number from 0 to \
                                 {MAX_NOISE}"
                            )
                        })?,
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

/// The most texture noise `--noise` takes: 1 mm (the models' own are 2–10 µm).
const MAX_NOISE: f64 = 1e-3;

/// The depth map, its width and whether it was a PNG, checked: PNGs as yarok writes them
/// (16-bit grey, their unit stated, millimetres without), converted to metres.
fn depth(path: &str) -> Result<(Vec<f32>, usize, bool), String> {
    let (depth, width, png) = if path.ends_with(".png") {
        let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
        let (width, _, metres) = depth_from_png(&bytes).map_err(|e| format!("{path}: {e}"))?;
        // A pixel without depth sees nothing: as far as the map's farthest.
        let farthest = metres
            .iter()
            .copied()
            .filter(|m| m.is_finite())
            .fold(0.0, f32::max);
        let filled = metres
            .iter()
            .map(|m| if m.is_finite() { *m } else { farthest })
            .collect();
        (filled, width as usize, true)
    } else {
        let array = npy::read(path).map_err(|e| e.to_string())?;
        match array.shape[..] {
            [_, width] => (array.data, width, false),
            _ => {
                return Err(format!(
                    "{path}: expected a 2-D array, got shape {:?}",
                    array.shape
                ));
            }
        }
    };
    check_depth(path, &depth, width)?;
    Ok((depth, width, png))
}

/// The largest depth a map may hold: 1 km (a z-buffer's values are at most 1).
const MAX_DEPTH: f32 = 1000.0;

/// Refuses a depth map with a value that is not a finite distance, or with nothing in it.
fn check_depth(path: &str, depth: &[f32], width: usize) -> Result<(), String> {
    if let Some(index) = depth
        .iter()
        .position(|d| !(d.is_finite() && (0.0..=MAX_DEPTH).contains(d)))
    {
        return Err(format!(
            "{path}: row {}, column {} holds {}, not a distance from 0 to {MAX_DEPTH} (metres)",
            index / width.max(1),
            index % width.max(1),
            depth[index]
        ));
    }
    if depth.iter().all(|d| *d == 0.0) {
        return Err(format!("{path}: every depth is 0: nothing was rendered"));
    }
    Ok(())
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

/// Runs `yarok tactile` with the arguments after `tactile`.
pub(super) fn run(args: &[String]) -> Result<(), String> {
    if args.first().is_some_and(|a| a == "calibrate") {
        return super::calibrate::run(&args[1..]);
    }
    let options = options(args)?;
    let inputs: Vec<&str> = [Some(options.depth), options.background, options.calibration]
        .into_iter()
        .flatten()
        .collect();
    super::apart_from_inputs(options.out, &inputs)?;
    let (depth, width, png) = depth(options.depth)?;
    if options.zbuffer && (png || options.sensor != "digit" || options.calibration.is_some()) {
        return Err(
            "--depth-unit zbuffer is for a .npy map given to the reference DIGIT model (digit, \
             no --calibration)"
                .to_owned(),
        );
    }
    let metric = !options.zbuffer;
    if let Some(path) = options.calibration {
        return calibrated(path, &options, &depth, width);
    }
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
        _ => {
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
    };
    let image = image::RgbImage::from_raw(width as u32, height as u32, image)
        .ok_or("internal: image size")?;
    super::write_png(image, options.out)
}

/// Renders `depth` with the calibration in `path` (the gel at the map's farthest value).
fn calibrated(
    path: &str,
    options: &Options<'_>,
    depth: &[f32],
    width: usize,
) -> Result<(), String> {
    let calibration = Calibration::load(path).map_err(|e| e.to_string())?;
    calibration
        .check_sensor(options.sensor)
        .map_err(|e| format!("{path}: {e}"))?;
    let height = depth.len() / width.max(1);
    if calibration.size() != (width, height) {
        let (w, h) = calibration.size();
        return Err(format!(
            "{path} is for {w}×{h} images, the depth map {} is {width}×{height}",
            options.depth
        ));
    }
    let gel = depth
        .iter()
        .copied()
        .filter(|d| d.is_finite())
        .fold(f32::NEG_INFINITY, f32::max);
    if !gel.is_finite() {
        return Err(format!("{}: no finite depth", options.depth));
    }
    let indentation: Vec<f32> = depth
        .iter()
        .map(|d| if d.is_finite() { gel - d } else { 0.0 })
        .collect();
    let pixels_per_mm = options
        .pixels_per_mm
        .unwrap_or(calibration.geometry().pixels_per_mm);
    let image = calibration
        .render_indentation(&indentation, 1e-3 / pixels_per_mm)
        .map_err(|e| format!("{}: {e}", options.depth))?;
    super::write_png(image, options.out)
}
