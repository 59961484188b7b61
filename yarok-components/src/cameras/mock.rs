//! [`BlackFrames`]: a [`Cam`] in `mock`.

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
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        let (width, height) = size(bind)?;
        Ok(Cam::with_feed(
            bind,
            std::rc::Rc::new(BlackFrames { width, height }),
        ))
    }
}
