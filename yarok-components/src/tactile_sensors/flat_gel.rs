//! [`FlatGelOptics`]: a flat gel in front of the camera, seen through a [`FlatGelModel`] (the
//! reference Phong model, or a calibrated one).

use super::kind::Optics;
use crate::tactile::SizeError;
use crate::tactile::phong::PhongModel;

/// How a flat gel's depth map becomes its image.
pub(super) trait FlatGelModel {
    /// The image of the gel at `depth` (metres from the camera, `width` columns) over
    /// `background`, into `out`.
    fn render_into(
        &mut self,
        depth: &[f32],
        width: usize,
        background: &[u8],
        out: &mut [u8],
    ) -> Result<(), SizeError>;
    /// Splits each image's work across rayon's threads (`true`) or not.
    #[cfg(feature = "parallel")]
    fn set_parallel(&mut self, parallel: bool);
}

impl FlatGelModel for PhongModel {
    fn render_into(
        &mut self,
        depth: &[f32],
        width: usize,
        background: &[u8],
        out: &mut [u8],
    ) -> Result<(), SizeError> {
        PhongModel::render_into(self, depth, width, background, out)
    }

    #[cfg(feature = "parallel")]
    fn set_parallel(&mut self, parallel: bool) {
        PhongModel::set_parallel(self, parallel);
    }
}

/// A flat gel `gel_face` in front of the camera, seen through `model`.
pub(super) struct FlatGelOptics<M> {
    pub(super) model: M,
    /// Image columns.
    pub(super) width: usize,
    /// Distance from the camera to the gel's outer face, and the gel's thickness (metres).
    pub(super) gel_face: f64,
    pub(super) thickness: f64,
    /// Half sizes (x, y) of the gel (metres).
    pub(super) gel: [f64; 2],
    /// Metres a pixel spans on the gel.
    pub(super) pixel: f64,
    /// The gel's face, at every pixel.
    pub(super) surface: Vec<f32>,
}

impl<M: FlatGelModel> Optics for FlatGelOptics<M> {
    fn surface(&self) -> &[f32] {
        &self.surface
    }

    fn thickness(&self) -> f64 {
        self.thickness
    }

    fn pixel_area(&self) -> f64 {
        self.pixel * self.pixel
    }

    fn surface_distance(&self, x: f64, y: f64) -> Option<f64> {
        let [half_x, half_y] = self.gel;
        (x.abs() <= half_x && y.abs() <= half_y).then_some(self.gel_face)
    }

    fn render(
        &mut self,
        depth: &[f32],
        background: &[u8],
        out: &mut [u8],
    ) -> Result<(), SizeError> {
        self.model.render_into(depth, self.width, background, out)
    }

    #[cfg(feature = "parallel")]
    fn set_parallel(&mut self, parallel: bool) {
        self.model.set_parallel(parallel);
    }
}
