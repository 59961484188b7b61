//! [`CameraFeed`]: where a [`Cam`](super::Cam)'s images come from in one environment.

use image::RgbImage;
use yarok_mjc::DepthImage;

use super::CamError;

/// A camera's images in one environment: MuJoCo's renderer, black frames in `mock`, a real
/// camera's newest frame, or a user's own (a replay, another renderer). The [`Cam`](super::Cam)
/// holds one and calls nothing else.
///
/// # Examples
///
/// Frames replayed from a recording, one per tick:
///
/// ```
/// use std::cell::RefCell;
///
/// use image::RgbImage;
/// use yarok_components::cameras::{CamError, CameraFeed};
///
/// struct Replayed(RefCell<std::vec::IntoIter<RgbImage>>);
///
/// impl CameraFeed for Replayed {
///     fn rgb(&self) -> Result<RgbImage, CamError> {
///         Ok(self.0.borrow_mut().next().unwrap_or_default())
///     }
/// }
/// ```
pub trait CameraFeed {
    /// The current colour image, top row first.
    ///
    /// # Errors
    ///
    /// When the image cannot be made.
    fn rgb(&self) -> Result<RgbImage, CamError>;

    /// The current depth image in metres (planar distance along the camera axis). By default
    /// none: a colour camera measures no depth.
    ///
    /// # Errors
    ///
    /// [`CamError::NoDepth`] by default; when the image cannot be made.
    fn depth(&self) -> Result<DepthImage, CamError> {
        Err(CamError::NoDepth)
    }

    /// The current colour and depth images of the same instant. By default each in turn.
    ///
    /// # Errors
    ///
    /// As [`CameraFeed::rgb`] and [`CameraFeed::depth`].
    fn rgbd(&self) -> Result<(RgbImage, DepthImage), CamError> {
        Ok((self.rgb()?, self.depth()?))
    }
}
