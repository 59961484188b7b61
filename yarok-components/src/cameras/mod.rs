//! Cameras.

use std::cell::RefCell;
use std::rc::Rc;

use image::RgbImage;
use yarok_core::compose::{Component, Declaration, Value};
use yarok_core::runtime::{Bind, RuntimeError};
use yarok_mjc::{CameraId, Data, DepthImage, RenderError, SharedRenderer, SimBind};

/// A camera: `read()` gives a colour image, `read_depth()` distances in metres.
///
/// Tag `cam`; config `width`, `height` (pixels, default 640×480) and `fovy` (degrees, default
/// 45). The camera looks down its body's −z axis with +y up; place it with a `<body>` around the
/// tag or `parent=` on a robot's body.
///
/// Environments: `sim` renders offscreen with MuJoCo; `mock` returns black images of the
/// configured size.
#[derive(Clone)]
pub struct Cam {
    interface: Rc<dyn CamInterface>,
}

impl std::fmt::Debug for Cam {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cam").finish_non_exhaustive()
    }
}

trait CamInterface {
    fn read(&self) -> Result<RgbImage, RenderError>;
    fn read_depth(&self) -> Result<DepthImage, RenderError>;
}

impl Cam {
    /// The current colour image, top row first.
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn read(&self) -> Result<RgbImage, RenderError> {
        self.interface.read()
    }

    /// The current depth image in metres (planar distance along the camera axis).
    ///
    /// # Errors
    ///
    /// When rendering fails.
    pub fn read_depth(&self) -> Result<DepthImage, RenderError> {
        self.interface.read_depth()
    }
}

impl Component for Cam {
    fn declaration() -> Declaration {
        Declaration::new("cam").default("width", 640).default("height", 480).default("fovy", 45.0).template(
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

    fn bind(bind: &mut Bind<'_>) -> Result<Self, RuntimeError> {
        let size = |key: &str| match bind.config().get(key) {
            Some(Value::Int(n)) if *n > 0 => {
                u32::try_from(*n).map_err(|_| bind.error(format!("{key} is too large")))
            }
            other => Err(bind.error(format!(
                "{key} must be a positive number of pixels, got {other:?}"
            ))),
        };
        let (width, height) = (size("width")?, size("height")?);
        let interface: Rc<dyn CamInterface> = match bind.environment() {
            "sim" => {
                let sim = bind.sim()?;
                let renderer = sim
                    .renderer(width, height)
                    .map_err(|e| bind.error(e.to_string()))?;
                Rc::new(SimCam {
                    renderer,
                    data: sim.data(),
                    camera: bind.camera_id("camera")?,
                })
            }
            "mock" => Rc::new(MockCam { width, height }),
            _ => return Err(bind.no_interface()),
        };
        Ok(Cam { interface })
    }
}

struct SimCam {
    renderer: SharedRenderer,
    data: Rc<RefCell<Data>>,
    camera: CameraId,
}

impl CamInterface for SimCam {
    fn read(&self) -> Result<RgbImage, RenderError> {
        self.renderer
            .borrow_mut()
            .render_rgb(&mut self.data.borrow_mut(), self.camera)
    }

    fn read_depth(&self) -> Result<DepthImage, RenderError> {
        self.renderer
            .borrow_mut()
            .render_depth(&mut self.data.borrow_mut(), self.camera)
    }
}

struct MockCam {
    width: u32,
    height: u32,
}

impl CamInterface for MockCam {
    fn read(&self) -> Result<RgbImage, RenderError> {
        Ok(RgbImage::new(self.width, self.height))
    }

    fn read_depth(&self) -> Result<DepthImage, RenderError> {
        Ok(DepthImage::new(self.width, self.height))
    }
}
