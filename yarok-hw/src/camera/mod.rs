//! Cameras on real hardware (feature `camera`): frames decoded from MJPEG and YUYV into RGB
//! images, and MJPEG streams read frame by frame.

mod decode;
mod mjpeg_stream;

pub use decode::{DecodeError, PixelFormat, decode};
pub use mjpeg_stream::{MjpegStream, StreamError};
