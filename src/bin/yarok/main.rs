//! The `yarok` command line.
//!
//! ```text
//! yarok --help
//! yarok run WORLD [--behaviour NAME] [--viewer] [--inspect] [--record FILE.mcap]
//!           [--profile foxglove|ros2] [--dataset DIR] [--video FILE.mp4] [--shard I/N] [--bridge]
//!           [--env ENV]
//!           [--set TARGET=VALUE]... [--config FILE]
//! yarok run --list
//! yarok compose WORLD [--set [/PATH/]KEY=VALUE]... [--out FILE]
//! yarok tactile digit|gelsight|geltip DEPTH OUT.png [--background PNG] [--geltip-params DIR]
//!               [--noise SIGMA] [--seed N] [--calibration FILE.json] [--pixels-per-mm PX]
//!               [--depth-unit m|zbuffer]
//! yarok tactile calibrate UNTOUCHED.png PRESSES.csv OUT.json --sensor NAME
//!               [--ball-diameter-mm MM] [--pixels-per-mm PX] [--contact-scale S,…]
//!               [--spread SIGMA,…] [--hold-out N]
//! ```
//!
//! `run` runs a bundled world (`pick_and_place_world`, …; `--list` lists them) with one of its
//! demo behaviours (the first by default), optionally watched in a window (`--viewer`; the
//! probes' images in another, `--inspect`: feature `viewer`), recorded in MCAP (`--profile ros2`:
//! as CDR-encoded ROS 2 messages that `ros2 bag` reads), recorded as a LeRobot v3 dataset
//! (`--dataset DIR`: feature `dataset`; `yarok::components::plugins::DatasetRecorder`) and filmed; while
//! standard error is a terminal it shows platform time, the real-time factor and ticks per
//! second. `--shard I/N` runs shard I (from 0) of N of the behaviour's work (see
//! `yarok::core::config::Shard`). `--bridge` publishes the world over Zenoh and takes commands
//! (feature `zenoh`; `yarok::components::plugins::ZenohBridge`). `--env`, `--set` and `--config`
//! are the platform's own options.
//!
//! `compose` writes the composed MJCF of WORLD — a bundled component's tag (e.g.
//! `tumble-tower`) or an MJCF template file, in which bundled components' tags may be used — to
//! standard output or FILE. `--set` overrides a config value of the world (`rows=4`) or of the
//! component at a path (`/tower/rows=4`).
//!
//! `tactile` turns a depth map into a tactile image with a sensor's optical model. DEPTH is a
//! 16-bit PNG in millimetres or a `.npy`/`.npy.gz` float array in metres (`--depth-unit zbuffer`:
//! the reference DIGIT model's raw z-buffer values). GelTip needs its geometry:
//! `--geltip-params DIR` with `bkg_depth_m.npy.gz` and `light_field_{0,1,2}.npy.gz`. With
//! `--calibration FILE` the image is that calibrated model's instead (the gel at the depth map's
//! farthest value). `tactile calibrate` fits a calibration to real frames of ball presses
//! (`yarok::components::tactile::calibration`).

mod calibrate;
mod compose;
mod run;
mod tactile;

use std::process::ExitCode;

use yarok::components::probe_images;

const USAGE: &str = "usage: yarok run WORLD [--behaviour NAME] [--viewer] [--inspect] [--record FILE.mcap]
                 [--profile foxglove|ros2] [--dataset DIR] [--video FILE.mp4] [--shard I/N] [--bridge]
                 [--env ENV] [--set TARGET=VALUE]... [--config FILE]
       yarok run --list
       yarok compose WORLD [--set [/PATH/]KEY=VALUE]... [--out FILE]
       yarok tactile digit|gelsight|geltip DEPTH OUT.png [--background PNG] [--noise SIGMA] [--seed N]
                     [--geltip-params DIR] [--light-fields files|linear|plane]
                     [--calibration FILE.json] [--pixels-per-mm PX] [--depth-unit m|zbuffer]
       yarok tactile calibrate UNTOUCHED.png PRESSES.csv OUT.json --sensor NAME
                     [--ball-diameter-mm 4.7] [--pixels-per-mm 19.58]
                     [--contact-scale 0.5,0.6,…,1] [--spread 6,10,…,26] [--hold-out N]
  WORLD  run: a bundled world's tag (see --list); compose: a bundled component's tag, or an
         MJCF template file
  DEPTH  a 16-bit grey PNG in the unit its depth_unit_m text states (millimetres without one),
         or a .npy/.npy.gz float32/float64 array in metres (--depth-unit zbuffer: the reference
         DIGIT model's raw z-buffer values, as its test data hold)
  DIR    GelTip geometry: bkg_depth_m.npy.gz (the membrane's depth) and, for --light-fields files
         (the default), light_field_{0,1,2}.npy.gz; linear and plane compute the fields for three
         LEDs on a 12.6 mm ring at the membrane's nearest depth
  FILE   a calibration (from calibrate): the image is the calibrated model's, the gel taken to
         be at the depth map's farthest value and PX (default the calibration's) its scale
  NAME   the sensor calibrated (digit, gelsight, or your own: letters, digits, _ and -), which
         the calibration states and what loads it checks
  PRESSES.csv  a header naming frame,center_x,center_y,radius_px (any order), a row a press
               (each frame once, its centre on the frame, 1 px <= radius <= half the frame);
               frames/FRAME.png beside it, all of one size and kind; --hold-out N
         leaves out the frames whose number is one less than a multiple of N; the ball's
         diameter 0.5-50 mm, pixels per mm 1-200, contact scales 0.05-3 (those that keep
         every press's contact circle within the ball are tried), spreads 0-64 px;
         beside OUT.json, OUT.coverage.png maps where the presses reached (beyond their
         rectangle the model holds the nearest covered weights); where the presses'
         imprints appear (an offset, a stretch from the middle) is fitted and printed";

/// Writes `text` to standard output; a closed standard output (`yarok … | head`) ends the
/// output quietly, as Unix tools do.
fn print(text: &str) -> Result<(), String> {
    yarok::core::stdout::write(text)
        .map(|_| ())
        .map_err(|e| format!("cannot write to standard output: {e}"))
}

/// How a command failed: its message, and the exit status.
struct Failure {
    message: String,
    status: u8,
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Self { message, status: 2 }
    }
}

/// Refuses an output file that is one of the command's `inputs` (the same file, by any path):
/// writing it would destroy what the command reads.
fn apart_from_inputs(output: &str, inputs: &[&str]) -> Result<(), String> {
    let Ok(written) = std::fs::canonicalize(output) else {
        return Ok(());
    };
    match inputs
        .iter()
        .find(|input| std::fs::canonicalize(input).is_ok_and(|read| read == written))
    {
        Some(input) => Err(format!(
            "the output {output} is the input {input}: writing it would destroy what is read; \
             give another output file"
        )),
        None => Ok(()),
    }
}

/// Writes `image` to `out` as PNG, replacing only a PNG yarok wrote.
fn write_png(image: image::RgbImage, out: &str) -> Result<(), String> {
    probe_images::save_png(image, out).map_err(|e| e.to_string())
}

fn main() -> ExitCode {
    let args = match yarok::core::args::from_process() {
        Ok(args) => args,
        Err(message) => {
            eprintln!("error: {message}");
            return ExitCode::from(2);
        }
    };
    let result = match args.first().map(String::as_str) {
        _ if args.iter().any(|a| a == "-h" || a == "--help") => {
            print(&format!("{USAGE}\n")).map_err(Failure::from)
        }
        Some("run") => run::run(&args[1..]),
        Some("compose") => compose::run(&args[1..]).map_err(Failure::from),
        Some("tactile") => tactile::run(&args[1..]).map_err(Failure::from),
        _ => Err(Failure::from(USAGE.to_owned())),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure { message, status }) => {
            eprintln!("error: {message}");
            ExitCode::from(status)
        }
    }
}
