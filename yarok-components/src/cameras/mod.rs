//! Cameras.

mod feed;
mod mock;
#[cfg(feature = "camera")]
pub(crate) mod real;
#[cfg(feature = "render")]
mod sim;

use std::rc::Rc;

use image::RgbImage;

use crate::probe_images;
use yarok_core::component::{
    Bind, BindError, Component, Declaration, Environment, Interfaces, Mock,
};
#[cfg(feature = "render")]
use yarok_mjc::RenderError;
use yarok_mjc::{DepthImage, Sim};

pub use feed::CameraFeed;
pub use mock::BlackFrames;

/// A camera: `read()` gives a colour image, `read_depth()` distances in metres.
///
/// Tag `cam`; config `width`, `height` (pixels, default 640×480), `fovy` (degrees, default 45),
/// `preset` (`"quality"`, the default: shadows, reflections, multisampling; `"fast"`: none of
/// those, several times faster on a CPU renderer) and `look`, the axis of its parent's frame it
/// looks along (`"-z"`, the default, as MuJoCo's cameras, +y up in the image; `"+x"`, `"-x"`,
/// `"+y"`, `"-y"`, +z up; `"+z"`: [`LOOK_DIRECTIONS`]), so that a camera on a link looks along
/// it with no hand-derived `xyaxes`. Place it with a `<body>` around the tag or `parent=` on a
/// robot's body or site. Its probes `rgb` and `depth` render when read.
///
/// Environments: `sim` renders offscreen with MuJoCo; `real` (feature `camera`) shows the
/// newest frame of a Video4Linux2 camera (interface setting `device`, e.g. `/dev/video0`, at
/// `fps`, default 30), of the MJPEG stream of a program it runs (`command`, e.g. ffmpeg or
/// GStreamer) or of a file or FIFO (`file`), and has no depth; `mock` renders the world as its
/// templates placed it and as mock drives have set its joints since (yarok's platform attaches
/// that declared world; with none, black images of the configured size).
#[derive(Clone)]
pub struct Cam {
    feed: Rc<dyn CameraFeed>,
}

impl std::fmt::Debug for Cam {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cam").finish_non_exhaustive()
    }
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
    /// A camera over `feed` (a user's own environment: a replay, another renderer), with the
    /// probes `rgb` and `depth`.
    pub fn with_feed<E: Environment>(bind: &mut Bind<E>, feed: Rc<dyn CameraFeed>) -> Self {
        let cam = Cam { feed };
        cam.show_probes(bind);
        cam
    }

    /// The current colour image, top row first.
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn read(&self) -> Result<RgbImage, CamError> {
        self.feed.rgb()
    }

    /// The current depth image in metres (planar distance along the camera axis).
    ///
    /// # Errors
    ///
    /// When rendering fails, or the camera measures no depth.
    pub fn read_depth(&self) -> Result<DepthImage, CamError> {
        self.feed.depth()
    }

    /// The current colour and depth images of the same instant, from one draw (cheaper than
    /// [`Cam::read`] and [`Cam::read_depth`] in turn).
    ///
    /// # Errors
    ///
    /// When rendering fails, or the camera measures no depth.
    pub fn read_rgbd(&self) -> Result<(RgbImage, DepthImage), CamError> {
        self.feed.rgbd()
    }
}

impl Cam {
    /// Registers the probes `rgb` and `depth`, each rendering when read.
    fn show_probes<E: Environment>(&self, bind: &mut Bind<E>) {
        let shown = self.clone();
        bind.probe("rgb", move || Ok(probe_images::rgb(shown.read()?)));
        let shown = self.clone();
        bind.probe("depth", move || {
            Ok(probe_images::depth(shown.read_depth()?, 1e-3))
        });
    }
}

/// The camera's config.
#[derive(serde::Serialize, serde::Deserialize)]
struct CamConfig {
    width: u32,
    height: u32,
    fovy: f64,
    preset: Preset,
    look: String,
}

/// The directions a camera may look along in its parent's frame (its `look` setting), each
/// with the camera frame's x and y axes (`xyaxes`) that point it there, image up toward +z (or
/// +y, looking along z).
pub const LOOK_DIRECTIONS: [(&str, &str); 6] = [
    ("-z", "1 0 0 0 1 0"),
    ("+z", "-1 0 0 0 1 0"),
    ("+x", "0 -1 0 0 0 1"),
    ("-x", "0 1 0 0 0 1"),
    ("+y", "1 0 0 0 0 1"),
    ("-y", "-1 0 0 0 0 1"),
];

/// How a simulated camera renders.
#[derive(Clone, Copy, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
enum Preset {
    Quality,
    Fast,
}

impl Component for Cam {
    fn declaration() -> Declaration {
        Declaration::new("cam")
            .config(CamConfig {
                width: 640,
                height: 480,
                fovy: 45.0,
                preset: Preset::Quality,
                look: "-z".to_owned(),
            })
            .template(
                r#"<mujoco>
                 <worldbody>
                   <body name="body">
                     <camera name="camera" fovy="{fovy}" xyaxes='{LOOK}'/>
                     <geom type="box" size="0.012 0.012 0.008" pos="0 0 0.009" rgba="0.15 0.15 0.15 1" contype="0" conaffinity="0"/>
                   </body>
                 </worldbody>
               </mujoco>"#
                    .replace("LOOK", &look_expression()),
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

/// The template expression giving the camera's `xyaxes` for its `look` setting.
fn look_expression() -> String {
    LOOK_DIRECTIONS
        .iter()
        .rev()
        .fold(String::from("\"\""), |otherwise, (direction, axes)| {
            format!(r#""{axes}" if look == "{direction}" else {otherwise}"#)
        })
}

/// The configured image size, each side at least one pixel (and the direction it looks
/// along, one of [`LOOK_DIRECTIONS`]).
fn size<E: Environment>(bind: &Bind<E>) -> Result<(u32, u32), BindError> {
    let CamConfig {
        width,
        height,
        look,
        ..
    } = bind.config()?;
    if !LOOK_DIRECTIONS
        .iter()
        .any(|(direction, _)| *direction == look)
    {
        return Err(bind.error(format!(
            "look {look:?} is not a direction: one of {}",
            LOOK_DIRECTIONS.map(|(direction, _)| direction).join(", ")
        )));
    }
    for (key, pixels) in [("width", width), ("height", height)] {
        if pixels == 0 {
            return Err(bind.error(format!("{key} must be at least one pixel")));
        }
    }
    Ok((width, height))
}

/// The configured render preset.
#[cfg(feature = "render")]
fn render_preset<E: Environment>(bind: &Bind<E>) -> Result<yarok_mjc::RenderPreset, BindError> {
    let CamConfig { preset, .. } = bind.config()?;
    Ok(match preset {
        Preset::Quality => yarok_mjc::RenderPreset::Quality,
        Preset::Fast => yarok_mjc::RenderPreset::Fast,
    })
}
