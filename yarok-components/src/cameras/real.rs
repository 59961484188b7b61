//! The [`Cam`]'s `real` interface (feature `camera`): frames of an MJPEG stream, written by a
//! program the interface runs (ffmpeg or GStreamer capturing a USB camera) or read from a file
//! or FIFO; the newest frame is what [`Cam::read`] returns.

use std::cell::RefCell;
use std::rc::Rc;

use image::RgbImage;
use serde::Deserialize;
use tokio::io::AsyncRead;
use yarok_core::component::{Bind, BindError, Interface};
use yarok_hw::Real;
use yarok_hw::camera::MjpegStream;

use super::{Cam, Source, size};

/// The interface settings of a real camera (`[interfaces."/path/to/cam"]`): exactly one of
/// `command` and `file`.
#[derive(Debug, Clone, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct Settings {
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
            command: Vec::new(),
            file: String::new(),
            first_frame_seconds: 5.0,
        }
    }
}

/// The newest frame the stream delivered.
#[derive(Debug)]
pub(super) struct RealFrames {
    latest: RefCell<RgbImage>,
}

impl RealFrames {
    pub(super) fn latest(&self) -> RgbImage {
        self.latest.borrow().clone()
    }
}

impl Interface<Real> for Cam {
    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        let (width, height) = size(bind)?;
        let settings: Settings = bind.settings()?;
        let (reader, name, program): (Box<dyn AsyncRead + Unpin>, String, _) =
            match (settings.command.split_first(), settings.file.is_empty()) {
                (Some((program, arguments)), true) => {
                    let mut child = tokio::process::Command::new(program)
                        .args(arguments)
                        .stdin(std::process::Stdio::null())
                        .stdout(std::process::Stdio::piped())
                        .kill_on_drop(true)
                        .spawn()
                        .map_err(|e| bind.error(format!("cannot run {program}: {e}")))?;
                    let stdout = child.stdout.take().expect("its output is piped");
                    (Box::new(stdout), program.clone(), Some(child))
                }
                (None, false) => {
                    let file = tokio::fs::File::open(&settings.file)
                        .await
                        .map_err(|e| bind.error(format!("{}: {e}", settings.file)))?;
                    (Box::new(file), settings.file.clone(), None)
                }
                _ => {
                    return Err(bind.error(
                        "set exactly one of `command` (a program writing an MJPEG stream) and \
                         `file` (a file or FIFO holding one)",
                    ));
                }
            };
        let mut stream = MjpegStream::new(reader, name.clone(), width, height);
        let first = bind
            .within(
                settings.first_frame_seconds,
                "the first frame",
                stream.next_frame(),
            )
            .await?
            .map_err(|e| bind.error(e))?
            .ok_or_else(|| bind.error(format!("{name} ended before its first frame")))?;
        let frames = Rc::new(RealFrames {
            latest: RefCell::new(first),
        });
        let newest = Rc::clone(&frames);
        let runs_program = program.is_some();
        bind.spawn(async move {
            while let Some(frame) = stream.next_frame().await? {
                *newest.latest.borrow_mut() = frame;
            }
            if runs_program {
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
        let cam = Cam {
            source: Source::Real(frames),
        };
        cam.show_probes(bind);
        Ok(cam)
    }
}
