//! Tactile data collection with rigs in parallel: `--rigs N` platforms (one per thread, default
//! 2, through `run_parallel`, sharing one compiled model) each run a [`TactileRigWorld`] — a
//! printer pressing a 4 mm sphere into a GelTip (or, with `--set sensor="digit"`, a DIGIT) —
//! over their shard of a grid of 5 × 5 points and 3 depths (the `collect` demo behaviour; the
//! same as `yarok run tactile_rig_world --behaviour collect --shard I/N` on N machines).
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
use std::path::Path;
use std::time::Instant;

use yarok::components::demos::{self, INDEX_HEADER};
use yarok::components::worlds::TactileRigWorld;
use yarok::core::runtime::run_parallel;

/// Rig `rig` of `rigs`: its shard of the grid, written to `out`.
fn run_rig(args: &[String], out: &str, rig: usize, rigs: usize) -> Result<(), String> {
    let collect = demos::find("tactile_rig_world")
        .and_then(|demo| demo.behaviour(Some("collect")))
        .ok_or("no collect demo")?;
    collect
        .install(yarok::platform().world::<TactileRigWorld>())
        // One rig has the cores to itself: its sensor model may use them all.
        .set(&format!("parallel={}", rigs == 1))
        .and_then(|builder| builder.set(&format!("platform/shard=\"{rig}/{rigs}\"")))
        .and_then(|builder| builder.set(&format!("behaviour/out={out:?}")))
        .and_then(|builder| builder.args(args.iter().cloned()))
        .and_then(|builder| builder.run())
        .map_err(|e| e.to_string())
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

/// Joins the shards' index files into `index.csv`, rows in the grid's order; the rows.
fn merge_indexes(out: &Path, rigs: usize) -> Result<Vec<String>, Box<dyn Error>> {
    let mut rows = Vec::new();
    for rig in 0..rigs {
        let part = out.join(format!("index_{rig}_of_{rigs}.csv"));
        rows.extend(
            std::fs::read_to_string(&part)?
                .lines()
                .skip(1)
                .map(str::to_owned),
        );
        std::fs::remove_file(part)?;
    }
    let number = |row: &String| row.split(',').next().and_then(|n| n.parse::<usize>().ok());
    rows.sort_by_key(number);
    let mut index = format!("{INDEX_HEADER}\n");
    for row in &rows {
        index.push_str(row);
        index.push('\n');
    }
    std::fs::write(out.join("index.csv"), index)?;
    Ok(rows)
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = yarok::core::args::from_process()?;
    let rigs: usize = take_option(&mut args, "--rigs")?.map_or(Ok(2), |n| n.parse())?;
    if rigs == 0 {
        return Err("--rigs must be at least 1".into());
    }
    let out = take_option(&mut args, "--out")?.unwrap_or_else(|| "out/tactile_rig".into());
    let started = Instant::now();
    let jobs: Vec<_> = (0..rigs)
        .map(|rig| {
            let (args, out) = (&args, &out);
            move || run_rig(args, out, rig, rigs)
        })
        .collect();
    run_parallel(jobs, rigs)
        .into_iter()
        .collect::<Result<Vec<()>, _>>()?;
    let elapsed = started.elapsed().as_secs_f64();
    let rows = if rigs == 1 {
        let index = std::fs::read_to_string(Path::new(&out).join("index.csv"))?;
        index.lines().skip(1).map(str::to_owned).collect()
    } else {
        merge_indexes(Path::new(&out), rigs)?
    };
    let felt = rows.iter().filter(|row| row.contains(",true,")).count();
    println!(
        "{} samples from {rigs} rig(s) in {elapsed:.2} s ({:.1} samples/s); {felt} felt the \
         press; written to {out}/index.csv",
        rows.len(),
        rows.len() as f64 / elapsed
    );
    if felt != rows.len() {
        return Err(format!("{} presses were not felt", rows.len() - felt).into());
    }
    Ok(())
}
