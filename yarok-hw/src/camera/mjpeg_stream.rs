//! [`MjpegStream`]: frames from a stream of concatenated JPEG images — a file, a pipe from
//! ffmpeg or GStreamer, an MJPEG camera's payload.

use image::RgbImage;
use tokio::io::{AsyncRead, AsyncReadExt};

use super::{DecodeError, PixelFormat, decode};

/// The largest frame kept; a stream that never ends a frame within it is an error.
const MAX_FRAME: usize = 16 << 20;

/// A frame could not be had from the stream.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StreamError {
    /// Reading failed.
    #[error("camera {camera}: {source}")]
    Io {
        /// The camera (its device or source).
        camera: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A frame did not decode.
    #[error("camera {camera}: {source}")]
    Decode {
        /// The camera.
        camera: String,
        /// Why.
        source: DecodeError,
    },
    /// No frame ended within 16 MiB: this is not an MJPEG stream.
    #[error("camera {camera}: no JPEG frame ends within {MAX_FRAME} bytes")]
    Unframed {
        /// The camera.
        camera: String,
    },
}

/// Frames of `width` × `height` from a stream of concatenated JPEG images: each runs from its
/// start-of-image marker (`FF D8`) to its end-of-image marker (`FF D9`); bytes between frames
/// are skipped.
///
/// # Cancel safety
///
/// [`MjpegStream::next_frame`] is cancel safe: bytes read are kept for the next call.
#[derive(Debug)]
pub struct MjpegStream<R> {
    reader: R,
    camera: String,
    width: u32,
    height: u32,
    buffer: Vec<u8>,
}

impl<R: AsyncRead + Unpin> MjpegStream<R> {
    /// Frames of `width` × `height` from `reader`, from the camera called `camera` in errors.
    pub fn new(reader: R, camera: impl Into<String>, width: u32, height: u32) -> Self {
        Self {
            reader,
            camera: camera.into(),
            width,
            height,
            buffer: Vec::new(),
        }
    }

    /// The next frame, or `None` at the end of the stream.
    ///
    /// # Errors
    ///
    /// [`StreamError`] naming the camera.
    pub async fn next_frame(&mut self) -> Result<Option<RgbImage>, StreamError> {
        loop {
            if let Some(frame) = self.take_frame() {
                return decode(PixelFormat::Mjpeg, self.width, self.height, &frame)
                    .map(Some)
                    .map_err(|source| StreamError::Decode {
                        camera: self.camera.clone(),
                        source,
                    });
            }
            if self.buffer.len() > MAX_FRAME {
                return Err(StreamError::Unframed {
                    camera: self.camera.clone(),
                });
            }
            let mut chunk = [0u8; 64 * 1024];
            let read = self
                .reader
                .read(&mut chunk)
                .await
                .map_err(|source| StreamError::Io {
                    camera: self.camera.clone(),
                    source,
                })?;
            if read == 0 {
                return Ok(None);
            }
            self.buffer.extend_from_slice(&chunk[..read]);
        }
    }

    /// The first whole frame in the buffer, removed from it with what came before.
    fn take_frame(&mut self) -> Option<Vec<u8>> {
        let start = find(&self.buffer, &[0xFF, 0xD8], 0)?;
        let end = find(&self.buffer, &[0xFF, 0xD9], start + 2)? + 2;
        let frame = self.buffer[start..end].to_vec();
        self.buffer.drain(..end);
        Some(frame)
    }
}

/// Where `marker` first occurs in `bytes` at or after `from`.
fn find(bytes: &[u8], marker: &[u8; 2], from: usize) -> Option<usize> {
    bytes
        .get(from..)?
        .windows(2)
        .position(|pair| pair == marker)
        .map(|at| at + from)
}
