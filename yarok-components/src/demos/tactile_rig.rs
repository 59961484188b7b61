//! The TactileRigWorld demo: the indenter pressed ever deeper into the sensor.

use yarok_core::runtime::{BehaviourResult, Pl};

use super::out_folder;
use crate::worlds::{Press, TactileRigWorld};

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
        sample.image.save(&path)?;
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
