//! [`ModelCameras`]: the cameras of the model a recorder was asked for, found by name, and the
//! renderer that renders them.

use std::sync::Arc;

use yarok_core::BoxError;
use yarok_mjc::{CameraId, Model, SimBackend};
#[cfg(feature = "render")]
use yarok_mjc::{RenderPreset, Renderer};

/// Cameras of a `sim` model, by name, rendered at one size.
#[derive(Debug, Default)]
pub(crate) struct ModelCameras {
    cameras: Vec<(String, CameraId)>,
    /// `None` when no camera was asked for: no renderer is made.
    renderer: Option<CameraRenderer>,
}

impl ModelCameras {
    /// Cameras `names` of `sim`'s model, rendered at `size` (with MuJoCo's shadows and
    /// reflections when `quality`).
    ///
    /// # Errors
    ///
    /// When the model has no camera of one of the names (naming it), or the renderer cannot be
    /// made.
    pub(crate) fn find(
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
        let renderer = make_renderer(model, size, quality)?;
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
    pub(crate) fn render(&mut self, sim: &SimBackend) -> Result<Vec<Vec<u8>>, BoxError> {
        let Some(renderer) = &mut self.renderer else {
            return Ok(Vec::new());
        };
        let mut images = Vec::with_capacity(self.cameras.len());
        for (_, camera) in &self.cameras {
            images.push(render_rgb(renderer, sim, *camera)?);
        }
        Ok(images)
    }
}

/// What renders a recorder's cameras: MuJoCo's offscreen renderer, or, built without the
/// `render` feature, nothing (no value of it exists).
#[cfg(feature = "render")]
type CameraRenderer = Renderer;
#[cfg(not(feature = "render"))]
#[derive(Debug)]
enum CameraRenderer {}

/// A renderer of `model`'s cameras at `size`, with MuJoCo's shadows and reflections when
/// `quality` (else the fast preset, which software GL renders several times faster).
#[cfg(feature = "render")]
fn make_renderer(
    model: &Arc<Model>,
    size: [u32; 2],
    quality: bool,
) -> Result<CameraRenderer, BoxError> {
    let preset = if quality {
        RenderPreset::Quality
    } else {
        RenderPreset::Fast
    };
    let [width, height] = size;
    Ok(Renderer::builder()
        .size(width, height)
        .preset(preset)
        .build(model)?)
}

#[cfg(not(feature = "render"))]
fn make_renderer(_: &Arc<Model>, _: [u32; 2], _: bool) -> Result<CameraRenderer, BoxError> {
    Err(
        "recording the model's cameras needs rendering: build yarok with its `render` feature"
            .into(),
    )
}

#[cfg(feature = "render")]
fn render_rgb(
    renderer: &mut CameraRenderer,
    sim: &SimBackend,
    camera: CameraId,
) -> Result<Vec<u8>, BoxError> {
    Ok(renderer.render_rgb(&mut sim.data_mut(), camera)?.into_raw())
}

#[cfg(not(feature = "render"))]
fn render_rgb(
    renderer: &mut CameraRenderer,
    _: &SimBackend,
    _: CameraId,
) -> Result<Vec<u8>, BoxError> {
    match *renderer {}
}
