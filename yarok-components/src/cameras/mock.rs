//! A [`Cam`] in `mock`: the declared world rendered as its mock drives leave it (where the
//! platform attached one, as yarok's does), else [`BlackFrames`].

use image::RgbImage;
use yarok_core::component::{Bind, BindError, Interface, Mock};
use yarok_mjc::DepthImage;

use super::{Cam, CamError, CameraFeed, size};

/// Black images, and depth 0, of a configured size.
#[derive(Debug, Clone, Copy)]
pub struct BlackFrames {
    /// Pixels across.
    pub width: u32,
    /// Pixels down.
    pub height: u32,
}

impl CameraFeed for BlackFrames {
    fn rgb(&self) -> Result<RgbImage, CamError> {
        Ok(RgbImage::new(self.width, self.height))
    }

    fn depth(&self) -> Result<DepthImage, CamError> {
        Ok(DepthImage::new(self.width, self.height))
    }
}

impl Interface<Mock> for Cam {
    /// With a declared world attached (yarok's platform attaches one), the camera renders it
    /// as the templates placed it and as mock drives have since set its joints; with none,
    /// black frames.
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        let (width, height) = size(bind)?;
        #[cfg(feature = "render")]
        if bind.backend().world::<yarok_mjc::DeclaredWorld>().is_some() {
            use yarok_mjc::MockBind;
            let preset = super::render_preset(bind)?;
            let camera = bind.declared_camera_with("camera", width, height, preset)?;
            return Ok(Cam::with_feed(bind, std::rc::Rc::new(camera)));
        }
        Ok(Cam::with_feed(
            bind,
            std::rc::Rc::new(BlackFrames { width, height }),
        ))
    }
}
