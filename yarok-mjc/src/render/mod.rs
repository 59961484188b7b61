//! [`Renderer`]: headless offscreen rendering of a model's cameras to RGB and metric depth.

mod egl;
#[cfg(feature = "viewer")]
mod gallery;
mod mujoco_scene;
mod reach;
#[cfg(feature = "viewer")]
mod view;
#[cfg(feature = "viewer")]
mod window;

#[cfg(feature = "viewer")]
pub use gallery::{Gallery, Picture, TextRow};
#[cfg(feature = "viewer")]
pub use view::{Corner, Overlay, View, Visual};
#[cfg(feature = "viewer")]
pub use window::{Button, Key, Window, WindowEvent};

use std::fmt;
use std::marker::PhantomData;
use std::rc::Rc;
use std::sync::Arc;

use image::RgbImage;

use crate::error::{LibraryError, ModelError};
use crate::model::{CameraId, GeomId, Model};
use crate::{Data, DepthImage, sys};
use egl::GlContext;
use mujoco_scene::{ContextSpec, make_scene, update_scene};

/// Rendering could not be set up or carried out.
#[derive(Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// libmujoco is unavailable.
    #[error(transparent)]
    Library(#[from] LibraryError),
    /// An EGL step failed: no usable GPU or Mesa driver, or no OpenGL support.
    #[error("EGL could not {step}: {reason}")]
    Egl {
        /// What was being done.
        step: &'static str,
        /// What EGL said.
        reason: String,
    },
    /// The image size, or the model's multisampling (`visual/quality/@offsamples`), is beyond
    /// what this OpenGL implementation can allocate for the renderer's offscreen buffer: past
    /// its size or sample limits, or its limit on a buffer's bytes (llvmpipe: 1 GiB, so 8192²
    /// with 4 samples at most).
    #[error(
        "an offscreen buffer of {width}x{height} with {samples} samples is beyond what this \
         OpenGL implementation allocates (at most {max_width}x{max_height} and {max_samples} \
         samples, within its limit on a buffer's bytes); render smaller images or lower \
         <visual><quality offsamples=\"..\"/></visual>"
    )]
    BeyondGl {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// `visual/quality/@offsamples` (0 with [`RenderPreset::Fast`]).
        samples: u32,
        /// The largest framebuffer width the implementation supports.
        max_width: u32,
        /// The largest framebuffer height the implementation supports.
        max_height: u32,
        /// The most samples the implementation supports.
        max_samples: u32,
    },
    /// A scene was asked to hold more geoms than [`MAX_GEOMS`].
    #[error("a scene of {requested} geoms is more than the {MAX_GEOMS} a renderer can hold")]
    TooManyGeoms {
        /// The requested number.
        requested: usize,
    },
    /// A zero width or height was requested.
    #[error("image size {width}x{height} has a zero side")]
    Empty {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
    },
    /// The data handed to the renderer belongs to another model.
    #[error("the data belongs to another model than the renderer was built for")]
    ModelMismatch,
    /// No X server to open a window on.
    #[error(
        "no window can open on display {display:?}: {reason} (set DISPLAY to a running X \
         server, or run headless: Xvfb, xvfb-run)"
    )]
    NoDisplay {
        /// `$DISPLAY`.
        display: String,
        /// What went wrong.
        reason: String,
    },
}

yarok_core::debug_as_report!(RenderError);

impl From<ModelError> for RenderError {
    fn from(error: ModelError) -> Self {
        match error {
            ModelError::Library(library) => Self::Library(library),
            _ => Self::ModelMismatch,
        }
    }
}

/// The most geoms [`RendererBuilder::max_geoms`] accepts (MuJoCo allocates the scene up front).
pub const MAX_GEOMS: usize = 1_000_000;

/// Rendering quality presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum RenderPreset {
    /// MuJoCo's defaults: shadows, reflections and the model's multisampling.
    #[default]
    Quality,
    /// No shadows, reflections or multisampling: several times faster on a CPU renderer.
    Fast,
    /// For cameras whose depth alone is used (a tactile sensor's): as [`RenderPreset::Fast`],
    /// and the model's textures are not uploaded, which makes the renderer start several times
    /// faster; colour images come untextured.
    Depth,
}

/// Builds a [`Renderer`]; see [`Renderer::builder`].
#[derive(Debug, Clone)]
pub struct RendererBuilder {
    width: u32,
    height: u32,
    preset: RenderPreset,
    max_geoms: usize,
}

impl RendererBuilder {
    /// Image size in pixels (default 640×480). The renderer's offscreen buffer is this size,
    /// whatever the model's `visual/global/@offwidth` and `@offheight`.
    pub fn size(mut self, width: u32, height: u32) -> Self {
        (self.width, self.height) = (width, height);
        self
    }

    /// Quality preset (default [`RenderPreset::Quality`]).
    pub fn preset(mut self, preset: RenderPreset) -> Self {
        self.preset = preset;
        self
    }

    /// How many geoms a scene can hold (default 10 000, at most [`MAX_GEOMS`]); extra geoms are
    /// not drawn.
    pub fn max_geoms(mut self, max_geoms: usize) -> Self {
        self.max_geoms = max_geoms;
        self
    }

    /// Creates the OpenGL context on the calling thread and uploads the model's meshes and
    /// textures.
    ///
    /// # Errors
    ///
    /// [`RenderError::Empty`] for a zero size, [`RenderError::BeyondGl`] when the offscreen
    /// buffer is more than OpenGL can allocate, [`RenderError::TooManyGeoms`], [`RenderError::Egl`] when no OpenGL context can be
    /// made.
    pub fn build(self, model: &Arc<Model>) -> Result<Renderer, RenderError> {
        let (width, height) = (self.width, self.height);
        if width == 0 || height == 0 {
            return Err(RenderError::Empty { width, height });
        }
        if self.max_geoms > MAX_GEOMS {
            return Err(RenderError::TooManyGeoms {
                requested: self.max_geoms,
            });
        }
        let gl = GlContext::for_this_thread()?;
        // mjr_makeContext reads the offscreen buffer's size and multisampling, and the textures
        // to upload, from the model: a buffer of the image's size, no multisampling unless in
        // quality, and no textures for depth.
        let spec = ContextSpec {
            offscreen: (width, height),
            multisampling: self.preset == RenderPreset::Quality,
            textures: self.preset != RenderPreset::Depth,
            font_scale: sys::mjFONTSCALE_100,
            buffer: sys::mjFB_OFFSCREEN,
        };
        // MuJoCo treats a framebuffer it cannot complete as a fatal error (the process aborts),
        // so the buffer is checked against the implementation's limits first.
        let samples = to_u32(spec.context_model(model).vis.quality.offsamples);
        let limits = gl.limits()?;
        if width > limits.max_size.0
            || height > limits.max_size.1
            || samples > limits.max_samples
            || !gl.completes(width, height, samples)?
        {
            return Err(RenderError::BeyondGl {
                width,
                height,
                samples,
                max_width: limits.max_size.0,
                max_height: limits.max_size.1,
                max_samples: limits.max_samples,
            });
        }
        let max_geoms = i32::try_from(self.max_geoms).unwrap_or(i32::MAX);
        let (scene, option, perturb) =
            make_scene(model, max_geoms, self.preset == RenderPreset::Quality);
        // SAFETY: the GL context is current on this thread, and the buffer within its limits.
        let mut context = unsafe { spec.make(model) };
        context.readDepthMap = sys::mjDEPTH_ZEROFAR as i32;
        let skybox = scene.flags[sys::mjRND_SKYBOX as usize];
        let extent = model.raw().stat.extent;
        let map = model.raw().vis.map;
        let pixels = width as usize * height as usize;
        Ok(Renderer {
            gl,
            scene,
            context,
            option,
            perturb,
            model: Arc::clone(model),
            width,
            height,
            skybox,
            reach: None,
            touching: None,
            near: f64::from(map.znear) * extent,
            far: f64::from(map.zfar) * extent,
            rgb: vec![0; 3 * pixels],
            depth: vec![0.0; pixels],
            _thread_bound: PhantomData,
        })
    }
}

/// Renders a model's cameras offscreen, without a window or a GPU.
///
/// The OpenGL context belongs to the thread that built the renderer, so a `Renderer` is neither
/// `Send` nor `Sync`. Images come top row first, as a camera sees them. Depth is planar distance
/// along the camera axis in metres; where nothing is drawn it is the far clipping plane
/// (`visual/map/@zfar` × the model's extent). Depth-only renders skip the skybox; renders with
/// colour draw it, and there the sky's depth is the skybox's own distance.
///
/// # Examples
///
/// ```
/// use std::sync::Arc;
/// use yarok_mjc::{Data, Model, RenderPreset, Renderer};
///
/// let model = Arc::new(Model::from_xml_str(
///     r#"<mujoco><worldbody>
///          <camera name="eye" pos="0 0 2"/>
///          <geom type="plane" size="1 1 0.1" rgba="1 0 0 1"/>
///        </worldbody></mujoco>"#,
/// )?);
/// let mut data = Data::new(&model)?;
/// data.forward();
/// let mut renderer = Renderer::builder().size(64, 48).preset(RenderPreset::Fast).build(&model)?;
/// let (rgb, depth) = renderer.render(&mut data, model.camera("eye")?)?;
/// assert_eq!(rgb.dimensions(), (64, 48));
/// assert!((depth.get_pixel(32, 24)[0] - 2.0).abs() < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Renderer {
    gl: Rc<GlContext>,
    scene: Box<sys::mjvScene>,
    context: Box<sys::mjrContext>,
    option: sys::mjvOption,
    perturb: sys::mjvPerturb,
    model: Arc<Model>,
    width: u32,
    height: u32,
    /// Whether colour renders draw the skybox (depth-only renders never do: it has no depth).
    skybox: u8,
    reach: Option<f64>,
    touching: Option<GeomId>,
    near: f64,
    far: f64,
    rgb: Vec<u8>,
    depth: Vec<f32>,
    _thread_bound: PhantomData<*const ()>,
}

impl Renderer {
    /// A builder with the defaults: 640×480, [`RenderPreset::Quality`], 10 000 geoms.
    pub fn builder() -> RendererBuilder {
        RendererBuilder {
            width: 640,
            height: 480,
            preset: RenderPreset::Quality,
            max_geoms: 10_000,
        }
    }

    /// Image width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Which geom groups (0–5, as in MJCF's `group`) the next renders draw; all by default.
    /// A tactile sensor's camera hides the sensor's own housing and gel this way.
    pub fn set_visible_groups(&mut self, visible: [bool; 6]) {
        self.option.geomgroup = visible.map(u8::from);
    }

    /// Draws only geoms that may come within `reach` metres of the camera (by their bounding
    /// spheres; planes by their distance), or every geom (`None`, the default). A tactile
    /// sensor's camera, which sees a few millimetres into its gel, skips the rest of the world
    /// this way.
    pub fn set_reach(&mut self, reach: Option<f64>) {
        self.reach = reach;
    }

    /// Draws only the geoms that could touch `geom`: their `contype` and `conaffinity` match
    /// its, and they are neither on its body nor on the body it is mounted on; no sites,
    /// decorations or visual-only geoms — or everything (`None`, the default). A tactile sensor's camera sees only what can press
    /// into its gel this way.
    pub fn set_touching(&mut self, geom: Option<GeomId>) {
        self.touching = geom;
    }

    /// Renders the colour image of `camera`.
    ///
    /// # Errors
    ///
    /// [`RenderError::ModelMismatch`] when `data` or `camera` belongs to another model;
    /// [`RenderError::Egl`] when the context cannot be made current.
    pub fn render_rgb(
        &mut self,
        data: &mut Data,
        camera: CameraId,
    ) -> Result<RgbImage, RenderError> {
        self.draw(data, camera, Channels::Rgb)?;
        Ok(self.rgb_image())
    }

    /// Renders the depth image of `camera`, in metres.
    ///
    /// # Errors
    ///
    /// As [`Renderer::render_rgb`].
    pub fn render_depth(
        &mut self,
        data: &mut Data,
        camera: CameraId,
    ) -> Result<DepthImage, RenderError> {
        let mut depth = DepthImage::new(self.width, self.height);
        self.render_depth_into(data, camera, &mut depth)?;
        Ok(depth)
    }

    /// Renders the depth image of `camera` into `depth`, reusing its memory (it is resized to
    /// the renderer's size if it differs).
    ///
    /// # Errors
    ///
    /// As [`Renderer::render_rgb`].
    pub fn render_depth_into(
        &mut self,
        data: &mut Data,
        camera: CameraId,
        depth: &mut DepthImage,
    ) -> Result<(), RenderError> {
        self.draw(data, camera, Channels::Depth)?;
        self.depth_into(depth);
        Ok(())
    }

    /// Renders colour and depth of `camera` from one draw.
    ///
    /// # Errors
    ///
    /// As [`Renderer::render_rgb`].
    pub fn render(
        &mut self,
        data: &mut Data,
        camera: CameraId,
    ) -> Result<(RgbImage, DepthImage), RenderError> {
        self.draw(data, camera, Channels::Both)?;
        let mut depth = DepthImage::new(self.width, self.height);
        self.depth_into(&mut depth);
        Ok((self.rgb_image(), depth))
    }

    fn draw(
        &mut self,
        data: &mut Data,
        camera: CameraId,
        channels: Channels,
    ) -> Result<(), RenderError> {
        if data.model().signature() != self.model.signature() || !self.model.owns(camera) {
            return Err(RenderError::ModelMismatch);
        }
        self.gl.make_current()?;
        let mut view = sys::mjvCamera {
            type_: sys::mjCAMERA_FIXED as i32,
            fixedcamid: i32::try_from(camera.index()).unwrap_or(-1),
            ..Default::default()
        };
        let viewport = sys::mjrRect {
            left: 0,
            bottom: 0,
            width: self.width as i32,
            height: self.height as i32,
        };
        let rgb = if channels.rgb() {
            self.rgb.as_mut_ptr()
        } else {
            std::ptr::null_mut()
        };
        let depth = if channels.depth() {
            self.depth.as_mut_ptr()
        } else {
            std::ptr::null_mut()
        };
        self.scene.flags[sys::mjRND_SKYBOX as usize] = if channels.rgb() { self.skybox } else { 0 };
        let mj = self.model.mj();
        // SAFETY: this renderer's GL context is current; model, data, option, perturbation,
        // camera and scene are valid and belong to the same model (checked above); the pixel
        // buffers hold width·height pixels, the viewport's size, or are null when unwanted.
        unsafe {
            update_scene(
                &self.model,
                data,
                &self.option,
                &self.perturb,
                &mut view,
                &mut self.scene,
            );
        }
        if let Some(reach) = self.reach {
            reach::keep_within(&mut self.scene, reach);
        }
        if let Some(touched) = self.touching {
            reach::keep_touching(&mut self.scene, &self.model, touched);
        }
        // SAFETY: as above; the scene holds a subset of the geoms mjv_updateScene made. The
        // thread's other renderers share the GL context, so this one binds its own buffer first.
        unsafe {
            mj.mjr_setBuffer(sys::mjFB_OFFSCREEN as i32, &mut *self.context);
            mj.mjr_render(viewport, &mut *self.scene, &*self.context);
            mj.mjr_readPixels(rgb, depth, viewport, &*self.context);
        }
        Ok(())
    }

    fn rgb_image(&self) -> RgbImage {
        let row = 3 * self.width as usize;
        let flipped = self
            .rgb
            .chunks_exact(row)
            .rev()
            .flatten()
            .copied()
            .collect();
        RgbImage::from_raw(self.width, self.height, flipped).expect("buffer sized width·height·3")
    }

    fn depth_into(&self, out: &mut DepthImage) {
        if out.dimensions() != (self.width, self.height) {
            *out = DepthImage::new(self.width, self.height);
        }
        let (near, far) = (self.near, self.far);
        let metres = |d: f32| (near * far / (near + f64::from(d) * (far - near))) as f32;
        let row = self.width as usize;
        let rows = self.depth.chunks_exact(row).rev();
        for (out, row) in out.chunks_exact_mut(row).zip(rows) {
            for (out, d) in out.iter_mut().zip(row) {
                *out = metres(*d);
            }
        }
    }
}

impl Drop for Renderer {
    fn drop(&mut self) {
        let mj = self.model.mj();
        if self.gl.make_current().is_ok() {
            // SAFETY: the context that owns these GL resources is current; both are freed once.
            unsafe { mj.mjr_freeContext(&mut *self.context) };
        }
        // SAFETY: the scene was made by mjv_makeScene and is freed once.
        unsafe { mj.mjv_freeScene(&mut *self.scene) };
    }
}

impl fmt::Debug for Renderer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Renderer")
            .field("width", &self.width)
            .field("height", &self.height)
            .finish()
    }
}

#[derive(Clone, Copy)]
enum Channels {
    Rgb,
    Depth,
    Both,
}

impl Channels {
    fn rgb(self) -> bool {
        matches!(self, Channels::Rgb | Channels::Both)
    }

    fn depth(self) -> bool {
        matches!(self, Channels::Depth | Channels::Both)
    }
}

fn to_u32(value: i32) -> u32 {
    u32::try_from(value).unwrap_or(0)
}
