//! [`ModelCameras`]: the cameras of the model a recorder was asked for, found by name, and the
//! renderer that renders them.

use yarok_core::BoxError;
use yarok_mjc::{CameraId, RenderPreset, Renderer, SimBackend};

/// Cameras of a `sim` model, by name, rendered at one size.
#[derive(Debug, Default)]
pub(super) struct ModelCameras {
    cameras: Vec<(String, CameraId)>,
    /// `None` when no camera was asked for: no renderer is made.
    renderer: Option<Renderer>,
}

impl ModelCameras {
    /// Cameras `names` of `sim`'s model, rendered at `size` (with MuJoCo's shadows and
    /// reflections when `quality`).
    ///
    /// # Errors
    ///
    /// When the model has no camera of one of the names (naming it), or the renderer cannot be
    /// made.
    pub(super) fn find(
        sim: &SimBackend,
        names: &[String],
        size: [u32; 2],
        quality: bool,
    ) -> Result<Self, BoxError> {
        if names.is_empty() {
            return Ok(Self::default());
        }
        let model = sim.model();
        let cameras = names
            .iter()
            .map(|name| {
                let camera = model
                    .camera(name)
                    .map_err(|e| format!("camera {name:?} to record: {e}"))?;
                Ok((name.clone(), camera))
            })
            .collect::<Result<_, BoxError>>()?;
        let [width, height] = size;
        let renderer = Renderer::builder()
            .size(width, height)
            .preset(preset(quality))
            .build(model)?;
        Ok(Self {
            cameras,
            renderer: Some(renderer),
        })
    }

    /// The cameras' names, in the order they were asked for.
    pub(super) fn names(&self) -> impl Iterator<Item = &str> {
        self.cameras.iter().map(|(name, _)| name.as_str())
    }

    /// Each camera's image now, RGB, in the order they were asked for.
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub(super) fn render(&mut self, sim: &SimBackend) -> Result<Vec<Vec<u8>>, BoxError> {
        let Some(renderer) = &mut self.renderer else {
            return Ok(Vec::new());
        };
        let mut images = Vec::with_capacity(self.cameras.len());
        for (_, camera) in &self.cameras {
            images.push(
                renderer
                    .render_rgb(&mut sim.data_mut(), *camera)?
                    .into_raw(),
            );
        }
        Ok(images)
    }
}

/// The render preset of a recorder's cameras: MuJoCo's defaults when `quality` is asked for,
/// else the fast one (software GL renders it several times faster).
fn preset(quality: bool) -> RenderPreset {
    if quality {
        RenderPreset::Quality
    } else {
        RenderPreset::Fast
    }
}
