//! The TactileRigWorld demos: the indenter pressed ever deeper into the sensor, and a grid of
//! presses collected as a dataset.

use yarok_core::BoxError;
use yarok_core::runtime::{BehaviourResult, Pl};

use super::out_folder;
use crate::tactile::npy::NpyArray;
use crate::worlds::{Press, Sample, TactileRigWorld};

/// In a [`TactileRigWorld`]: presses the indenter into the sensor's centre 0.5, 1 and 1.5 mm
/// deep and saves each tactile image (`OUT/press_N.png`, OUT the behaviour's setting `out`,
/// default `out`). Fails if the sensor feels a press less as it goes deeper.
pub async fn press(pl: Pl) -> BehaviourResult {
    let rig: TactileRigWorld = pl.get("/")?;
    let out = out_folder(&pl)?;
    let mut deepest = 0.0;
    for (index, depth) in [0.0005, 0.001, 0.0015].into_iter().enumerate() {
        let sample = rig
            .press(Press {
                at: [0.0, 0.0],
                depth,
            })
            .await?;
        let path = format!("{out}/press_{index}.png");
        crate::probe_images::save_png(sample.image, &path)?;
        let felt = sample.contact.max_indentation;
        pl.log(format!(
            "t = {:.2} s: {} pressed {:.1} mm deep, felt {:.2} mm over {:.1} mm² → {path}",
            pl.time(),
            rig.sensor_kind(),
            depth * 1e3,
            felt * 1e3,
            sample.contact.area * 1e6
        ));
        if !sample.contact.in_contact || felt <= deepest {
            return Err(format!("the sensor felt {:.2} mm of a deeper press", felt * 1e3).into());
        }
        deepest = felt;
    }
    Ok(())
}

/// [`collect`]'s behaviour settings: where, and the grid it presses.
#[derive(serde::Deserialize)]
struct CollectSettings {
    out: std::path::PathBuf,
    points: usize,
    spacing_mm: f64,
    depths_mm: Vec<f64>,
}

/// The header of a collection's index.
pub const INDEX_HEADER: &str = "index,sensor,x_mm,y_mm,depth_mm,head_x_mm,head_y_mm,head_z_mm,\
                                in_contact,max_indentation_mm,area_mm2,image,depth";

/// The presses of a collection: `points` × `points` positions `spacing` metres apart around
/// the sensor's axis, at each depth in turn.
pub fn grid(points: usize, spacing: f64, depths: &[f64]) -> Vec<Press> {
    let offset = |i: usize| (i as f64 - (points as f64 - 1.0) / 2.0) * spacing;
    let mut presses = Vec::with_capacity(points * points * depths.len());
    for depth in depths {
        for y in 0..points {
            for x in 0..points {
                presses.push(Press {
                    at: [offset(x), offset(y)],
                    depth: *depth,
                });
            }
        }
    }
    presses
}

/// In a [`TactileRigWorld`]: presses a grid — the behaviour's `points` × `points` positions
/// (default 5) `spacing_mm` apart (2), at each of `depths_mm` ([0.5, 1, 1.5]) — and writes
/// every sample to `out`: the tactile image (`0007.png`), the depth its camera saw
/// (`0007_depth.npy`, metres, float32) and a row of the index (`index.csv`, columns
/// [`INDEX_HEADER`]). Each press is an episode ([`Pl::begin_episode`]): it starts from the
/// world's start state, whatever came before, and a recorder writes it apart. In a sharded run
/// (`[platform] shard = "I/N"`) it presses only its share of the grid (press `k` is shard
/// `k mod N`'s) and writes `index_I_of_N.csv`: the N shards' files and episode recordings are,
/// between them, the whole run's, byte for byte.
pub async fn collect(pl: Pl) -> BehaviourResult {
    let rig: TactileRigWorld = pl.get("/")?;
    let settings: CollectSettings = pl.config().deserialize()?;
    let CollectSettings {
        out,
        points,
        spacing_mm,
        depths_mm,
    } = settings;
    std::fs::create_dir_all(&out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let depths: Vec<f64> = depths_mm.iter().map(|d| d * 1e-3).collect();
    let shard = pl.shard();
    let mut index = String::from(INDEX_HEADER);
    index.push('\n');
    for (number, press) in shard.select(grid(points, spacing_mm * 1e-3, &depths)) {
        pl.begin_episode(number as u64)?;
        let sample = rig.press(press).await?;
        index.push_str(&write_sample(&out, rig.sensor_kind(), number, &sample)?);
        index.push('\n');
    }
    pl.end_episode();
    let name = if shard.is_whole() {
        "index.csv".to_owned()
    } else {
        format!("index_{}_of_{}.csv", shard.index, shard.count)
    };
    yarok_core::output_file::write_output(
        &out.join(&name),
        "index of presses",
        index_by_yarok,
        index.as_bytes(),
    )?;
    pl.log(format!("shard {shard}: {} → {}", name, out.display()));
    Ok(())
}

/// Whether the file at `path` is an index of presses yarok wrote: its first line is
/// [`INDEX_HEADER`].
fn index_by_yarok(path: &std::path::Path) -> std::io::Result<bool> {
    let head = yarok_core::output::head(path, INDEX_HEADER.len() as u64 + 1)?;
    Ok(head.strip_prefix(INDEX_HEADER.as_bytes()) == Some(b"\n"))
}

/// Writes sample `number`'s image and depth into `out`; its index row.
fn write_sample(
    out: &std::path::Path,
    sensor: &str,
    number: usize,
    sample: &Sample,
) -> Result<String, BoxError> {
    let (image, depth) = (format!("{number:04}.png"), format!("{number:04}_depth.npy"));
    crate::probe_images::save_png(sample.image.clone(), out.join(&image))?;
    let (width, height) = sample.depth.dimensions();
    NpyArray {
        shape: vec![height as usize, width as usize],
        data: sample.depth.as_raw().clone(),
    }
    .write(out.join(&depth))?;
    let [x, y] = sample.press.at.map(|m| m * 1e3);
    let [hx, hy, hz] = sample.head;
    let contact = &sample.contact;
    Ok(format!(
        "{number},{sensor},{x},{y},{},{hx},{hy},{hz},{},{},{},{image},{depth}",
        sample.press.depth * 1e3,
        contact.in_contact,
        contact.max_indentation * 1e3,
        contact.area * 1e6,
    ))
}
