//! Tactile data collection with rigs in parallel: `--rigs N` platforms (one per thread, default
//! 2) each run a [`TactileRigWorld`] — a printer pressing a 4 mm sphere into a GelTip (or, with
//! `--set sensor="digit"`, a DIGIT) — over their share of a grid of 5 × 5 points and 3 depths.
//! Every sample is written to `--out` (default `out/tactile_rig`): the tactile image
//! (`0000.png`), the depth its camera saw (`0000_depth.npy`, metres, float32) and a row of
//! `index.csv`. The files are the same, byte for byte, whatever the number of rigs.
//!
//! ```text
//! cargo run --release --example tactile_rig [-- --rigs 2 --out out/tactile_rig --set sensor="digit"]
//! ```
//!
//! With as many rigs as cores, set `LP_NUM_THREADS=0`: Mesa's llvmpipe then rasterises on each
//! rig's own thread instead of handing every small frame to threads of its own (on 2 cores,
//! 2 rigs collect 1.9× the samples of one this way, 1.6× without).
//!
//! In Python:
//!
//! ```text
//! import csv, numpy, PIL.Image
//! rows = list(csv.DictReader(open("out/tactile_rig/index.csv")))
//! image = numpy.asarray(PIL.Image.open("out/tactile_rig/" + rows[0]["image"]))
//! depth = numpy.load("out/tactile_rig/" + rows[0]["depth"])
//! ```

use std::error::Error;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use yarok::components::tactile::npy::NpyArray;
use yarok::components::worlds::{Press, Sample, TactileRigWorld};

/// The presses: 5 × 5 points 2 mm apart around the sensor's axis, each 0.5, 1 and 1.5 mm deep.
fn grid() -> Vec<Press> {
    let steps = [-0.004, -0.002, 0.0, 0.002, 0.004];
    let mut presses = Vec::new();
    for depth in [0.0005, 0.001, 0.0015] {
        for y in steps {
            for x in steps {
                presses.push(Press { at: [x, y], depth });
            }
        }
    }
    presses
}

/// What one rig collected: its sensor's kind, and its samples with their indices in the grid.
#[derive(Default)]
struct Collected {
    sensor: String,
    samples: Vec<(usize, Sample)>,
}

/// One rig's samples of `presses` (with their indices in the grid), set up by `args`.
fn run_rig(
    args: &[String],
    parallel_model: bool,
    presses: Vec<(usize, Press)>,
) -> Result<Collected, String> {
    let out = std::rc::Rc::new(std::cell::RefCell::new(Collected::default()));
    let collected = std::rc::Rc::clone(&out);
    yarok::platform()
        .world::<TactileRigWorld>()
        .set(&format!("parallel={parallel_model}"))
        .and_then(|builder| builder.args(args.iter().cloned()))
        .map_err(|e| e.to_string())?
        .behaviour(move |pl| async move {
            let rig: TactileRigWorld = pl.get("/")?;
            collected.borrow_mut().sensor = rig.sensor_kind().to_owned();
            for (index, press) in presses {
                let sample = rig.press(press).await?;
                collected.borrow_mut().samples.push((index, sample));
            }
            Ok(())
        })
        .run()
        .map_err(|e| e.to_string())?;
    Ok(out.take())
}

/// Takes `--name VALUE` out of `args`.
fn take_option(args: &mut Vec<String>, name: &str) -> Result<Option<String>, String> {
    let Some(at) = args.iter().position(|arg| arg == name) else {
        return Ok(None);
    };
    if at + 1 >= args.len() {
        return Err(format!("{name} needs a value"));
    }
    let value = args.remove(at + 1);
    args.remove(at);
    Ok(Some(value))
}

/// Writes each sample's files and the index.
fn write(out: &Path, sensor: &str, samples: &[(usize, Sample)]) -> Result<(), Box<dyn Error>> {
    std::fs::create_dir_all(out)?;
    let mut index = String::from(
        "index,sensor,x_mm,y_mm,depth_mm,head_x_mm,head_y_mm,head_z_mm,\
         in_contact,max_indentation_mm,area_mm2,image,depth\n",
    );
    for (number, sample) in samples {
        let (image, depth) = (format!("{number:04}.png"), format!("{number:04}_depth.npy"));
        sample.image.save(out.join(&image))?;
        let (width, height) = sample.depth.dimensions();
        NpyArray {
            shape: vec![height as usize, width as usize],
            data: sample.depth.as_raw().clone(),
        }
        .write(out.join(&depth))?;
        let [x, y] = sample.press.at.map(|m| m * 1e3);
        let [hx, hy, hz] = sample.head;
        let contact = &sample.contact;
        writeln!(
            index,
            "{number},{sensor},{x},{y},{},{hx},{hy},{hz},{},{},{},{image},{depth}",
            sample.press.depth * 1e3,
            contact.in_contact,
            contact.max_indentation * 1e3,
            contact.area * 1e6,
        )?;
    }
    std::fs::write(out.join("index.csv"), index)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let rigs: usize = take_option(&mut args, "--rigs")?.map_or(Ok(2), |n| n.parse())?;
    if rigs == 0 {
        return Err("--rigs must be at least 1".into());
    }
    let out = take_option(&mut args, "--out")?.unwrap_or_else(|| "out/tactile_rig".into());
    let presses = grid();
    let started = Instant::now();
    let results = std::thread::scope(|scope| {
        let rigs: Vec<_> = (0..rigs)
            .map(|rig| {
                let share: Vec<(usize, Press)> = presses
                    .iter()
                    .copied()
                    .enumerate()
                    .filter(|(index, _)| index % rigs == rig)
                    .collect();
                let args = &args;
                // One rig has the cores to itself: its sensor model may use them all.
                scope.spawn(move || run_rig(args, rigs == 1, share))
            })
            .collect();
        rigs.into_iter()
            .map(|rig| rig.join().map_err(|_| "a rig panicked".to_string())?)
            .collect::<Result<Vec<_>, _>>()
    })?;
    let elapsed = started.elapsed().as_secs_f64();
    let sensor = results
        .first()
        .map(|rig| rig.sensor.clone())
        .unwrap_or_default();
    let mut samples: Vec<(usize, Sample)> =
        results.into_iter().flat_map(|rig| rig.samples).collect();
    samples.sort_by_key(|(index, _)| *index);
    write(Path::new(&out), &sensor, &samples)?;
    let felt = samples.iter().filter(|(_, s)| s.contact.in_contact).count();
    println!(
        "{} {sensor} samples from {rigs} rig(s) in {elapsed:.2} s ({:.1} samples/s); {felt} felt \
         the press; written to {out}/index.csv",
        samples.len(),
        samples.len() as f64 / elapsed
    );
    if felt != samples.len() {
        return Err(format!("{} presses were not felt", samples.len() - felt).into());
    }
    Ok(())
}
