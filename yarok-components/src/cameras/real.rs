//! Real camera feeds (feature `camera`): the [`Cam`]'s `real` interface, and the frames every
//! camera-based component (tactile sensors too) reads on real hardware — from a Video4Linux2
//! device, from the MJPEG stream of a program the interface runs (ffmpeg, GStreamer), or from a
//! file or FIFO. The newest frame is what `read()` returns.

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use image::RgbImage;
use serde::Deserialize;
use tokio::io::AsyncRead;
use yarok_core::component::{Bind, BindError, Interface};
use yarok_hw::Real;
use yarok_hw::camera::{MjpegStream, StreamError, VideoDevice};

use super::{Cam, CamError, CameraFeed, size};

/// The interface settings of a real camera (`[interfaces."/path/to/cam"]`): exactly one of
/// `device`, `command` and `file`, and optionally `fps`, `size` and `first_frame_seconds`.
#[derive(Debug, Clone, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct Settings {
    /// A Video4Linux2 capture device, e.g. `/dev/video0` or `/dev/v4l/by-id/…`.
    device: String,
    /// Frames a second asked of the device (it may offer the nearest it has); the component's
    /// rate when unset.
    fps: Option<u32>,
    /// The frames' width and height in pixels; the component's when unset (a DIGIT's VGA
    /// stream: `[640, 480]` with `fps = 30`).
    size: Option<[u32; 2]>,
    /// A program and its arguments whose standard output is an MJPEG stream, e.g.
    /// `["ffmpeg", "-f", "v4l2", "-input_format", "mjpeg", "-i", "/dev/video0", "-c", "copy",
    /// "-f", "mjpeg", "pipe:1"]`.
    command: Vec<String>,
    /// A file or FIFO holding an MJPEG stream.
    file: String,
    /// Seconds the first frame may take.
    first_frame_seconds: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            device: String::new(),
            fps: None,
            size: None,
            command: Vec::new(),
            file: String::new(),
            first_frame_seconds: 5.0,
        }
    }
}

/// The newest frame a real camera delivered, and the platform time it arrived.
#[derive(Debug)]
pub(crate) struct RealFrames {
    latest: RefCell<RgbImage>,
    time: Cell<f64>,
}

impl CameraFeed for RealFrames {
    fn rgb(&self) -> Result<RgbImage, CamError> {
        Ok(self.latest())
    }
}

impl RealFrames {
    pub(crate) fn latest(&self) -> RgbImage {
        self.latest.borrow().clone()
    }

    /// Platform time (seconds) the newest frame arrived.
    pub(crate) fn time(&self) -> f64 {
        self.time.get()
    }
}

/// Where frames come from.
enum Feed {
    Device(VideoDevice),
    Stream(MjpegStream<Box<dyn AsyncRead + Unpin>>),
}

impl Feed {
    async fn next_frame(&mut self) -> Result<Option<RgbImage>, StreamError> {
        match self {
            Feed::Device(device) => device.next_frame().await,
            Feed::Stream(stream) => stream.next_frame().await,
        }
    }
}

/// Starts the component's camera feed as its interface settings say, waits for the first
/// frame, and keeps the newest one from then on (a task of the run; a feed that fails or, for a
/// device or program, ends, ends the run). Frames are `width` × `height` and `fps` is the rate
/// asked of a device unless the settings say otherwise.
pub(crate) async fn bind_frames(
    bind: &mut Bind<Real>,
    width: u32,
    height: u32,
    fps: u32,
) -> Result<Rc<RealFrames>, BindError> {
    let settings: Settings = bind.settings()?;
    let [width, height] = settings.size.unwrap_or([width, height]);
    if width == 0 || height == 0 {
        return Err(bind.error("size must be at least one pixel each way"));
    }
    let (mut feed, name, program) = open(bind, &settings, width, height, fps).await?;
    let first = bind
        .within(
            settings.first_frame_seconds,
            "the first frame",
            feed.next_frame(),
        )
        .await?
        .map_err(|e| bind.error(e))?
        .ok_or_else(|| bind.error(format!("{name} ended before its first frame")))?;
    let clock = bind.clock();
    let frames = Rc::new(RealFrames {
        latest: RefCell::new(first),
        time: Cell::new(clock.time()),
    });
    let newest = Rc::clone(&frames);
    let endless = !matches!(feed, Feed::Stream(_)) || program.is_some();
    bind.spawn(async move {
        while let Some(frame) = feed.next_frame().await? {
            *newest.latest.borrow_mut() = frame;
            newest.time.set(clock.time());
        }
        if endless {
            Err(format!("{name} stopped sending frames").into())
        } else {
            Ok(())
        }
    });
    if let Some(mut program) = program {
        // Killed and reaped at shutdown, so that nothing is left running.
        bind.on_stop(async move {
            program.kill().await?;
            Ok(())
        });
    }
    Ok(frames)
}

/// Opens the feed the settings name: the feed, its name in errors, and the program it runs.
async fn open(
    bind: &Bind<Real>,
    settings: &Settings,
    width: u32,
    height: u32,
    fps: u32,
) -> Result<(Feed, String, Option<tokio::process::Child>), BindError> {
    let stream = |reader: Box<dyn AsyncRead + Unpin>, name: &str| {
        Feed::Stream(MjpegStream::new(reader, name, width, height))
    };
    let chosen = (
        !settings.device.is_empty(),
        settings.command.split_first(),
        !settings.file.is_empty(),
    );
    match chosen {
        (true, None, false) => {
            let fps = settings.fps.unwrap_or(fps);
            let device = VideoDevice::open(&settings.device, width, height, fps)
                .map_err(|e| bind.error(e))?;
            Ok((Feed::Device(device), settings.device.clone(), None))
        }
        (false, Some((program, arguments)), false) => {
            let mut child = tokio::process::Command::new(program)
                .args(arguments)
                .stdin(std::process::Stdio::null())
                .stdout(std::process::Stdio::piped())
                .kill_on_drop(true)
                .spawn()
                .map_err(|e| bind.error(format!("cannot run {program}: {e}")))?;
            let stdout = child.stdout.take().expect("its output is piped");
            Ok((
                stream(Box::new(stdout), program),
                program.clone(),
                Some(child),
            ))
        }
        (false, None, true) => {
            let file = tokio::fs::File::open(&settings.file)
                .await
                .map_err(|e| bind.error(format!("{}: {e}", settings.file)))?;
            Ok((
                stream(Box::new(file), &settings.file),
                settings.file.clone(),
                None,
            ))
        }
        _ => Err(bind.error(
            "set exactly one of `device` (a Video4Linux2 camera), `command` (a program writing \
             an MJPEG stream) and `file` (a file or FIFO holding one)",
        )),
    }
}

/// Reads the settings of a real camera's feed, touching no device.
pub(crate) fn check_settings(bind: &Bind<Real>) -> Result<(), BindError> {
    bind.settings::<Settings>().map(drop)
}

impl Interface<Real> for Cam {
    fn check(bind: &Bind<Real>) -> Result<(), BindError> {
        check_settings(bind)
    }

    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        let (width, height) = size(bind)?;
        let frames = bind_frames(bind, width, height, 30).await?;
        Ok(Cam::with_feed(bind, frames))
    }
}
