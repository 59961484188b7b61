//! Cameras.

#[cfg(feature = "camera")]
pub(crate) mod real;

use image::RgbImage;

use crate::probe_images;
use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces, Mock};
#[cfg(feature = "render")]
use yarok_mjc::{Camera, RenderError, RenderPreset, SimBind};
use yarok_mjc::{DepthImage, Sim};

/// A camera: `read()` gives a colour image, `read_depth()` distances in metres.
///
/// Tag `cam`; config `width`, `height` (pixels, default 640×480), `fovy` (degrees, default 45)
/// and `preset` (`"quality"`, the default: shadows, reflections, multisampling; `"fast"`: none
/// of those, several times faster on a CPU renderer). The camera looks down its body's −z axis
/// with +y up; place it with a `<body>` around the tag or `parent=` on a robot's body. Its
/// probes `rgb` and `depth` render when read.
///
/// Environments: `sim` renders offscreen with MuJoCo; `real` (feature `camera`) shows the
/// newest frame of a Video4Linux2 camera (interface setting `device`, e.g. `/dev/video0`, at
/// `fps`, default 30), of the MJPEG stream of a program it runs (`command`, e.g. ffmpeg or
/// GStreamer) or of a file or FIFO (`file`), and has no depth; `mock` returns black images of
/// the configured size.
#[derive(Clone, Debug)]
pub struct Cam {
    source: Source,
}

#[derive(Clone, Debug)]
enum Source {
    #[cfg(feature = "render")]
    Sim(Camera),
    #[cfg(feature = "camera")]
    Real(std::rc::Rc<real::RealFrames>),
    Mock {
        width: u32,
        height: u32,
    },
}

/// A camera could not give an image.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CamError {
    /// Rendering failed (`sim`).
    #[cfg(feature = "render")]
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The camera measures no depth (a real colour camera).
    #[error("this camera measures no depth")]
    NoDepth,
}

impl Cam {
    /// The current colour image, top row first.
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn read(&self) -> Result<RgbImage, CamError> {
        match &self.source {
            #[cfg(feature = "render")]
            Source::Sim(camera) => Ok(camera.rgb()?),
            #[cfg(feature = "camera")]
            Source::Real(frames) => Ok(frames.latest()),
            Source::Mock { width, height } => Ok(RgbImage::new(*width, *height)),
        }
    }

    /// The current depth image in metres (planar distance along the camera axis).
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn read_depth(&self) -> Result<DepthImage, CamError> {
        match &self.source {
            #[cfg(feature = "render")]
            Source::Sim(camera) => Ok(camera.depth()?),
            #[cfg(feature = "camera")]
            Source::Real(_) => Err(CamError::NoDepth),
            Source::Mock { width, height } => Ok(DepthImage::new(*width, *height)),
        }
    }

    /// The current colour and depth images of the same instant, from one draw (cheaper than
    /// [`Cam::read`] and [`Cam::read_depth`] in turn).
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn read_rgbd(&self) -> Result<(RgbImage, DepthImage), CamError> {
        match &self.source {
            #[cfg(feature = "render")]
            Source::Sim(camera) => Ok(camera.rgbd()?),
            #[cfg(feature = "camera")]
            Source::Real(_) => Err(CamError::NoDepth),
            Source::Mock { width, height } => Ok((
                RgbImage::new(*width, *height),
                DepthImage::new(*width, *height),
            )),
        }
    }
}

impl Cam {
    /// Registers the probes `rgb` and `depth`, each rendering when read.
    fn show_probes<E: yarok_core::component::Environment>(&self, bind: &mut Bind<E>) {
        let shown = self.clone();
        bind.probe("rgb", move || Ok(probe_images::rgb(shown.read()?)));
        let shown = self.clone();
        bind.probe("depth", move || {
            Ok(probe_images::depth(shown.read_depth()?, 1e-3))
        });
    }
}

impl Component for Cam {
    fn declaration() -> Declaration {
        Declaration::new("cam").default("width", 640).default("height", 480).default("fovy", 45.0).default("preset", "quality").template(
            r#"<mujoco>
                 <worldbody>
                   <body name="body">
                     <camera name="camera" fovy="{fovy}"/>
                     <geom type="box" size="0.012 0.012 0.008" pos="0 0 0.009" rgba="0.15 0.15 0.15 1" contype="0" conaffinity="0"/>
                   </body>
                 </worldbody>
               </mujoco>"#,
        )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        #[cfg(feature = "render")]
        interfaces.add::<Sim>();
        #[cfg(not(feature = "render"))]
        interfaces.unavailable::<Sim>("the `render` feature");
        interfaces.add::<Mock>();
        #[cfg(feature = "camera")]
        interfaces.add::<yarok_hw::Real>();
        #[cfg(not(feature = "camera"))]
        interfaces.unavailable::<yarok_hw::Real>("the `camera` feature");
    }
}

/// The configured image size, each side at least one pixel.
fn size<E: yarok_core::component::Environment>(bind: &Bind<E>) -> Result<(u32, u32), BindError> {
    let side = |key: &str| -> Result<u32, BindError> {
        match bind.config_value::<u32>(key)? {
            0 => Err(bind.error(format!("{key} must be at least one pixel"))),
            pixels => Ok(pixels),
        }
    };
    Ok((side("width")?, side("height")?))
}

#[cfg(feature = "render")]
impl Interface<Sim> for Cam {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let (width, height) = size(bind)?;
        let preset = match bind.config_value::<String>("preset")?.as_str() {
            "quality" => RenderPreset::Quality,
            "fast" => RenderPreset::Fast,
            other => {
                return Err(bind.error(format!(
                    "preset must be \"quality\" or \"fast\", not {other:?}"
                )));
            }
        };
        let cam = Cam {
            source: Source::Sim(bind.camera_with("camera", width, height, preset)?),
        };
        cam.show_probes(bind);
        Ok(cam)
    }
}

impl Interface<Mock> for Cam {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        let (width, height) = size(bind)?;
        let cam = Cam {
            source: Source::Mock { width, height },
        };
        cam.show_probes(bind);
        Ok(cam)
    }
}
