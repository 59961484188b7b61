//! Sensors with a flat gel in front of the camera (DIGIT, GelSight), seen through the Phong
//! optical model or a calibrated one.

use yarok_core::component::Declaration;

use super::calibrated::CalibratedModel;
use super::flat_gel::FlatGelOptics;
use super::kind::{Optics, SensorConfig, SensorKind};
use crate::tactile::calibration::Calibration;
use crate::tactile::elastomer::Elastomer;
use crate::tactile::phong::{PhongModel, PhongParams};

/// What makes one sensor of the kind: its image, its gel and camera, its model and rate.
#[derive(Debug, Clone, Copy)]
pub(super) struct Spec {
    pub(super) tag: &'static str,
    /// Image columns and rows.
    pub(super) width: u32,
    pub(super) height: u32,
    /// Distance from the camera to the gel's outer face, and the gel's thickness (metres).
    pub(super) gel_face: f64,
    pub(super) thickness: f64,
    /// Half sizes (x, y) of the housing and of the gel (metres).
    pub(super) housing: [f64; 2],
    pub(super) gel: [f64; 2],
    /// The optical model's parameters (lights, metres per pixel, …); its depths are set from
    /// `gel_face` and `thickness`.
    pub(super) model: fn() -> PhongParams,
    /// How deep the gel sinks under a force.
    pub(super) elastomer: Elastomer,
    /// The calibration bundled for the sensor (`calibration = "bundled"`, then the default).
    pub(super) bundled: Option<fn() -> Calibration>,
    /// Frames per second by default: the real sensor's.
    pub(super) fps: f64,
    /// Whether the real sensor's camera lies across the image (see `SensorKind::turned`).
    #[cfg(feature = "camera")]
    pub(super) turned: bool,
}

impl Spec {
    /// The optical model's parameters for this geometry.
    fn params(&self) -> PhongParams {
        PhongParams {
            elastomer_thickness: self.thickness,
            min_depth: self.gel_face - self.thickness,
            ..(self.model)()
        }
    }

    /// This gel seen through `model`.
    fn flat_gel<M>(&self, model: M) -> FlatGelOptics<M> {
        FlatGelOptics {
            model,
            width: self.width as usize,
            gel_face: self.gel_face,
            thickness: self.thickness,
            gel: self.gel,
            pixel: self.params().px2m_ratio,
            surface: vec![self.gel_face as f32; (self.width * self.height) as usize],
        }
    }

    /// The camera's vertical field of view (degrees) that spans the model's image at the gel.
    fn field_of_view(&self) -> f64 {
        let half = f64::from(self.height) / 2.0 * self.params().px2m_ratio;
        2.0 * (half / self.gel_face).atan().to_degrees()
    }
}

/// The gel's and the camera's geometry the optical model is made for: template values that
/// cannot be set.
#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FlatGelGeometry {
    /// Distance from the camera to the gel's outer face, and the gel's thickness (metres).
    gel_face: f64,
    thickness: f64,
    /// Half sizes (x, y) of the gel (metres).
    gel: [f64; 2],
    /// The camera's vertical field of view (degrees).
    fovy: f64,
}

impl Spec {
    /// The geometry its optical model is made for.
    pub(super) fn geometry(&self) -> FlatGelGeometry {
        FlatGelGeometry {
            gel_face: self.gel_face,
            thickness: self.thickness,
            gel: self.gel,
            fovy: self.field_of_view(),
        }
    }
}

impl SensorKind for Spec {
    fn declaration(&self) -> Declaration {
        let calibration = if self.bundled.is_some() {
            "bundled"
        } else {
            "none"
        };
        Declaration::new(self.tag)
            .config(SensorConfig::new(self.fps, true, calibration))
            .config(self.geometry())
            .default("housing", self.housing)
            .template(include_str!("phong.xml"))
    }

    fn gel(&self) -> &'static str {
        "gel"
    }

    fn elastomer(&self) -> Elastomer {
        self.elastomer
    }

    fn fovy(&self) -> f64 {
        self.field_of_view()
    }

    fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    #[cfg(feature = "camera")]
    fn turned(&self) -> bool {
        self.turned
    }

    fn reach(&self) -> f64 {
        let pixel = self.params().px2m_ratio;
        let half = [self.width, self.height].map(|side| f64::from(side) / 2.0 * pixel);
        self.gel_face.hypot(half[0].hypot(half[1]))
    }

    fn bundled_calibration(&self) -> Option<Calibration> {
        self.bundled.map(|calibration| calibration())
    }

    fn optics(
        &self,
        seed: u64,
        noise: bool,
        calibration: Option<Calibration>,
    ) -> Result<Box<dyn Optics>, String> {
        let base = self.params();
        if let Some(calibration) = calibration {
            let noise_seed = noise.then_some(seed);
            let model = CalibratedModel::new(
                calibration,
                self.gel_face,
                base.px2m_ratio,
                self.size(),
                noise_seed,
            )?;
            return Ok(Box::new(self.flat_gel(model)));
        }
        let params = PhongParams {
            seed,
            texture_sigma: if noise { base.texture_sigma } else { 0.0 },
            ..base
        };
        Ok(Box::new(self.flat_gel(PhongModel::new(params))))
    }
}
