//! The PrinterWorld demo: the printer's camera surveys the tower.

use yarok_core::runtime::{BehaviourResult, Pl};

use super::out_folder;
use crate::cameras::Cam;
use crate::robots::AnetA30;

/// Head positions in millimetres: around the tower, then straight above it.
const POSES: [[f64; 3]; 4] = [
    [40.0, 40.0, 420.0],
    [280.0, 40.0, 420.0],
    [280.0, 280.0, 420.0],
    [160.0, 160.0, 400.0],
];

/// In a [`PrinterWorld`](crate::worlds::PrinterWorld): moves the head through a few poses, waits
/// for it to arrive (in platform time), and saves what the camera sees at each as PNG
/// (`OUT/printer_camera_N.png`, OUT the behaviour's setting `out`, default `out`).
pub async fn survey(pl: Pl) -> BehaviourResult {
    let printer: AnetA30 = pl.get("/printer")?;
    let camera: Cam = pl.get("/printer/cam")?;
    let out = out_folder(&pl)?;
    for (index, pose) in POSES.into_iter().enumerate() {
        let target = printer.move_to(pose);
        pl.wait(|| printer.is_at(target)).timeout(10.0).await?;
        pl.wait_seconds(0.2).await?; // let the head settle before the shot
        let path = format!("{out}/printer_camera_{index}.png");
        crate::probe_images::save_png(camera.read()?, &path)?;
        pl.log(format!(
            "t = {:5.2} s  head at {:?} mm  → {path}",
            pl.time(),
            printer.at().map(|mm| mm.round())
        ));
    }
    Ok(())
}
