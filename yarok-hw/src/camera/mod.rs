//! Cameras on real hardware (feature `camera`): frames captured from Video4Linux2 devices,
//! MJPEG streams read frame by frame, both decoded from MJPEG or YUYV into RGB images.

mod decode;
mod mjpeg_stream;
mod video_device;

pub use decode::{DecodeError, PixelFormat, decode};
pub use mjpeg_stream::{MjpegStream, StreamError};
pub use video_device::{CaptureError, VideoDevice};
