//! [`VideoDevice`]: frames captured from a Video4Linux2 device (a USB camera, a DIGIT) through
//! the `v4l` crate, on a thread of its own, decoded into RGB images.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use image::RgbImage;
use tokio::sync::Notify;
use v4l::buffer::Type;
use v4l::capability::Flags;
use v4l::io::traits::CaptureStream;
use v4l::video::Capture;
use v4l::{Device, Format, FourCC};

use super::{PixelFormat, StreamError, decode};

/// How long the capture thread waits for a frame before it looks whether it should stop: the
/// longest dropping a [`VideoDevice`] can take.
const POLL: Duration = Duration::from_millis(200);

/// Frames in a row that may fail to decode before capture ends with an error.
const CORRUPT_IN_A_ROW: u32 = 10;

/// Kernel buffers the device fills in turn.
const BUFFERS: u32 = 4;

/// A video device could not be set up for capture.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CaptureError {
    /// The device could not be opened or asked (missing, busy, no permission).
    #[error("camera {device}: {source}")]
    Open {
        /// The device.
        device: String,
        /// Why.
        source: std::io::Error,
    },
    /// The device is not a video capture device that streams.
    #[error("camera {device}: not a video capture device ({reason})")]
    NotACamera {
        /// The device.
        device: String,
        /// What it lacks.
        reason: String,
    },
    /// The device offers neither MJPEG nor YUYV frames at the size asked for.
    #[error("camera {device}: no MJPEG or YUYV frames of {width}x{height} (it offers {offered})")]
    Format {
        /// The device.
        device: String,
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
        /// The format the device gave instead.
        offered: String,
    },
}

/// What the capture thread leaves for [`VideoDevice::next_frame`]: the newest frame, or how
/// capture ended.
#[derive(Default)]
struct Latest {
    frame: Option<Result<RgbImage, StreamError>>,
    ended: bool,
}

/// Frames of `width` × `height` captured from a Video4Linux2 device: MJPEG when the device
/// offers it, YUYV otherwise, at the frame rate asked for (or the nearest the device offers).
/// A thread of its own dequeues and decodes the frames; only the newest waits to be taken, so a
/// slow reader gets the latest frame rather than a queue of old ones.
///
/// ```no_run
/// # async fn run() -> Result<(), Box<dyn std::error::Error>> {
/// use yarok_hw::camera::VideoDevice;
///
/// // A DIGIT's VGA stream.
/// let mut digit = VideoDevice::open("/dev/video0", 640, 480, 30)?;
/// if let Some(frame) = digit.next_frame().await? {
///     frame.save("digit.png")?;
/// }
/// # Ok(()) }
/// ```
///
/// # Cancel safety
///
/// [`VideoDevice::next_frame`] is cancel safe: a frame not taken stays for the next call (or is
/// replaced by a newer one).
pub struct VideoDevice {
    device: String,
    format: PixelFormat,
    fps: f64,
    latest: Arc<Mutex<Latest>>,
    arrived: Arc<Notify>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl std::fmt::Debug for VideoDevice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VideoDevice")
            .field("device", &self.device)
            .field("format", &self.format)
            .field("fps", &self.fps)
            .finish()
    }
}

impl VideoDevice {
    /// Opens `device` (e.g. `/dev/video0`, or a stable `/dev/v4l/by-id/…` name), sets it to
    /// `width` × `height` at `fps` frames a second and starts capturing.
    ///
    /// # Errors
    ///
    /// [`CaptureError`] naming the device: it cannot be opened, is no capture device, or offers
    /// neither MJPEG nor YUYV at that size.
    pub fn open(device: &str, width: u32, height: u32, fps: u32) -> Result<Self, CaptureError> {
        let open = |source| CaptureError::Open {
            device: device.to_owned(),
            source,
        };
        let camera = Device::with_path(device).map_err(open)?;
        let capabilities = camera
            .query_caps()
            .map_err(|source| CaptureError::NotACamera {
                device: device.to_owned(),
                reason: source.to_string(),
            })?;
        let needed = Flags::VIDEO_CAPTURE | Flags::STREAMING;
        if !capabilities.capabilities.contains(needed) {
            return Err(CaptureError::NotACamera {
                device: device.to_owned(),
                reason: format!("it offers {}", capabilities.capabilities),
            });
        }
        let format = negotiate(&camera, device, width, height)?;
        let params = camera
            .set_params(&v4l::video::capture::Parameters::with_fps(fps.max(1)))
            .map_err(open)?;
        let interval = params.interval;
        let fps = f64::from(interval.denominator) / f64::from(interval.numerator.max(1));
        let mut stream = v4l::io::mmap::Stream::with_buffers(&camera, Type::VideoCapture, BUFFERS)
            .map_err(open)?;
        stream.set_timeout(POLL);
        let latest = Arc::new(Mutex::new(Latest::default()));
        let arrived = Arc::new(Notify::new());
        let stop = Arc::new(AtomicBool::new(false));
        let capture = Capturing {
            device: device.to_owned(),
            format,
            width,
            height,
            latest: Arc::clone(&latest),
            arrived: Arc::clone(&arrived),
            stop: Arc::clone(&stop),
        };
        let thread = std::thread::Builder::new()
            .name(format!("camera {device}"))
            .spawn(move || capture.run(camera, stream))
            .map_err(open)?;
        Ok(Self {
            device: device.to_owned(),
            format,
            fps,
            latest,
            arrived,
            stop,
            thread: Some(thread),
        })
    }

    /// The encoding the device sends.
    pub fn format(&self) -> PixelFormat {
        self.format
    }

    /// The frame rate the device agreed to.
    pub fn fps(&self) -> f64 {
        self.fps
    }

    /// The next frame captured after the last one taken; `None` once capture has ended.
    ///
    /// # Errors
    ///
    /// [`StreamError`] naming the camera: the device failed (unplugged), or a frame did not
    /// decode.
    pub async fn next_frame(&mut self) -> Result<Option<RgbImage>, StreamError> {
        loop {
            let arrived = self.arrived.notified();
            {
                let mut latest = self.latest.lock().unwrap_or_else(|e| e.into_inner());
                if let Some(frame) = latest.frame.take() {
                    return frame.map(Some);
                }
                if latest.ended {
                    return Ok(None);
                }
            }
            arrived.await;
        }
    }
}

impl Drop for VideoDevice {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(thread) = self.thread.take() {
            // Within POLL: the thread looks at `stop` after every frame or timeout.
            let _ = thread.join();
        }
    }
}

/// Sets MJPEG, or else YUYV, at `width` × `height`.
fn negotiate(
    camera: &Device,
    device: &str,
    width: u32,
    height: u32,
) -> Result<PixelFormat, CaptureError> {
    let mut offered = String::new();
    for (fourcc, format) in [(b"MJPG", PixelFormat::Mjpeg), (b"YUYV", PixelFormat::Yuyv)] {
        let wanted = Format::new(width, height, FourCC::new(fourcc));
        let got = camera
            .set_format(&wanted)
            .map_err(|source| CaptureError::Open {
                device: device.to_owned(),
                source,
            })?;
        if got.fourcc == wanted.fourcc && (got.width, got.height) == (width, height) {
            return Ok(format);
        }
        offered = format!("{} {}x{}", got.fourcc, got.width, got.height);
    }
    Err(CaptureError::Format {
        device: device.to_owned(),
        width,
        height,
        offered,
    })
}

/// The capture thread's side.
struct Capturing {
    device: String,
    format: PixelFormat,
    width: u32,
    height: u32,
    latest: Arc<Mutex<Latest>>,
    arrived: Arc<Notify>,
    stop: Arc<AtomicBool>,
}

impl Capturing {
    /// Dequeues and decodes frames until told to stop or the device fails. A corrupt frame
    /// (USB cameras send one now and then) is skipped; [`CORRUPT_IN_A_ROW`] in a row end the
    /// capture with the decoder's error.
    fn run(self, camera: Device, mut stream: v4l::io::mmap::Stream<'static>) {
        let mut corrupt = 0;
        while !self.stop.load(Ordering::Relaxed) {
            let frame = match CaptureStream::next(&mut stream) {
                Err(error) if error.kind() == std::io::ErrorKind::TimedOut => continue,
                Err(source) => Err(StreamError::Io {
                    camera: self.device.clone(),
                    source,
                }),
                Ok((bytes, meta)) => {
                    let used = bytes.get(..meta.bytesused as usize).unwrap_or(bytes);
                    match decode(self.format, self.width, self.height, used) {
                        Ok(frame) => Ok(frame),
                        Err(error) if corrupt + 1 < CORRUPT_IN_A_ROW => {
                            corrupt += 1;
                            tracing::warn!(camera = %self.device, "skipped a frame: {error}");
                            continue;
                        }
                        Err(source) => Err(StreamError::Decode {
                            camera: self.device.clone(),
                            source,
                        }),
                    }
                }
            };
            corrupt = 0;
            let failed = frame.is_err();
            self.publish(|latest| latest.frame = Some(frame));
            if failed {
                break;
            }
        }
        drop(stream);
        drop(camera);
        self.publish(|latest| latest.ended = true);
    }

    fn publish(&self, change: impl FnOnce(&mut Latest)) {
        change(&mut self.latest.lock().unwrap_or_else(|e| e.into_inner()));
        self.arrived.notify_one();
    }
}
