//! A [`Cam`] in `sim`: MuJoCo renders what its camera sees, offscreen.

use image::RgbImage;
use yarok_core::component::{Bind, BindError, Interface};
use yarok_mjc::{Camera, DepthImage, Sim, SimBind};

use super::{Cam, CamError, CameraFeed, render_preset, size};

impl CameraFeed for Camera {
    fn rgb(&self) -> Result<RgbImage, CamError> {
        Ok(Camera::rgb(self)?)
    }

    fn depth(&self) -> Result<DepthImage, CamError> {
        Ok(Camera::depth(self)?)
    }

    /// Both from one draw.
    fn rgbd(&self) -> Result<(RgbImage, DepthImage), CamError> {
        Ok(Camera::rgbd(self)?)
    }
}

impl Interface<Sim> for Cam {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let (width, height) = size(bind)?;
        let preset = render_preset(bind)?;
        let camera = bind.camera_with("camera", width, height, preset)?;
        Ok(Cam::with_feed(bind, std::rc::Rc::new(camera)))
    }
}
