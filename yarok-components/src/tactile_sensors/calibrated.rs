//! [`CalibratedModel`]: a flat gel's image by a [`Calibration`] fitted to a real sensor.

use super::flat_gel::FlatGelModel;
use crate::tactile::SizeError;
use crate::tactile::calibration::{Calibration, RenderBuffers};
use crate::tactile::noise::CameraNoise;

/// A calibration's model of a flat gel `gel_face` metres from the camera, `pixel` metres a
/// pixel there. It draws its own untouched gel (the calibration's), not the sensor's background,
/// and, with noise, adds a pattern of the calibration's camera noise.
pub(super) struct CalibratedModel {
    calibration: Calibration,
    gel_face: f32,
    pixel: f64,
    indentation: Vec<f32>,
    buffers: RenderBuffers,
    noise: Option<CameraNoise>,
}

impl CalibratedModel {
    /// The model, if `calibration` makes images of the sensor's `size` (columns, rows); with
    /// the calibration's camera noise seeded by `noise_seed`, if given.
    pub(super) fn new(
        calibration: Calibration,
        gel_face: f64,
        pixel: f64,
        size: (u32, u32),
        noise_seed: Option<u64>,
    ) -> Result<Self, String> {
        let (width, height) = calibration.size();
        if (width as u32, height as u32) != size {
            return Err(format!(
                "the calibration makes {width}×{height} images, the sensor's are {}×{}",
                size.0, size.1
            ));
        }
        let noise = noise_seed
            .map(|seed| CameraNoise::new(calibration.noise_levels(), width * height * 3, seed));
        Ok(Self {
            calibration,
            gel_face: gel_face as f32,
            pixel,
            indentation: Vec::with_capacity(width * height),
            buffers: RenderBuffers::default(),
            noise,
        })
    }
}

impl FlatGelModel for CalibratedModel {
    fn render_into(
        &mut self,
        depth: &[f32],
        _width: usize,
        _background: &[u8],
        out: &mut [u8],
    ) -> Result<(), SizeError> {
        self.indentation.clear();
        self.indentation
            .extend(depth.iter().map(|d| (self.gel_face - d).max(0.0)));
        self.calibration.render_indentation_into(
            &self.indentation,
            self.pixel,
            &mut self.buffers,
            out,
        )?;
        if let Some(noise) = &self.noise {
            noise.add(out);
        }
        Ok(())
    }

    #[cfg(feature = "parallel")]
    fn set_parallel(&mut self, _parallel: bool) {}
}
