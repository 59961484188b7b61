//! [`Encoder`]: an `ffmpeg` process fed raw frames from a thread of its own, every wait on it
//! bounded: an encoder that stops reading ends the run with an error instead of blocking it.

use std::io::{Read, Write};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{SyncSender, sync_channel};
use std::thread::JoinHandle;
use std::time::Duration;

use yarok_core::BoxError;

use super::bounded_wait::{Refused, poll_within, send_within};

/// Frames queued for the encoder before the platform waits for it.
const QUEUED_FRAMES: usize = 8;

/// How long the encoder may take no frame before it is taken as stalled.
const STALL: Duration = Duration::from_secs(5);

/// How long the encoder may take to write the file once its input has ended.
const FINISH: Duration = Duration::from_secs(60);

/// How an [`H264`] video is encoded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct H264 {
    /// Width and height (even numbers, as `yuv420p` needs).
    pub(super) size: [u32; 2],
    /// Frames a second.
    pub(super) fps: f64,
    /// Frames from one keyframe to the next (`None`: the encoder's choice).
    pub(super) keyframe_interval: Option<u32>,
    /// x264's constant rate factor (`None`: its default, 23); lower is closer to the input.
    pub(super) crf: Option<u32>,
}

impl H264 {
    /// The pixel format the video is stored in.
    pub(super) const PIXEL_FORMAT: &str = "yuv420p";

    /// `ffmpeg` reading raw RGB frames on its standard input and writing them to `path` as
    /// H.264 in MP4, its index at the front.
    pub(super) fn ffmpeg(&self, path: &std::path::Path) -> Command {
        let [width, height] = self.size;
        let mut command = Command::new("ffmpeg");
        command
            .args(["-loglevel", "error", "-y", "-f", "rawvideo"])
            .args(["-pix_fmt", "rgb24", "-s", &format!("{width}x{height}")])
            .args(["-r", &self.fps.to_string(), "-i", "-"])
            .args(["-c:v", "libx264", "-pix_fmt", Self::PIXEL_FORMAT]);
        if let Some(interval) = self.keyframe_interval {
            command.args(["-g", &interval.to_string()]);
        }
        if let Some(crf) = self.crf {
            command.args(["-crf", &crf.to_string()]);
        }
        command.args(["-movflags", "+faststart"]).arg(path);
        command
    }
}

/// An encoder process writing `path` from the frames it is sent; killed and reaped when
/// dropped unfinished.
#[derive(Debug)]
pub(super) struct Encoder {
    path: PathBuf,
    process: Child,
    frames: Option<SyncSender<Vec<u8>>>,
    feeder: Option<JoinHandle<()>>,
    complaints: Option<JoinHandle<String>>,
}

impl Encoder {
    /// Starts `command` (which reads raw frames on its standard input and writes `path`).
    ///
    /// # Errors
    ///
    /// When the program cannot be started.
    pub(super) fn start(mut command: Command, path: PathBuf) -> Result<Self, BoxError> {
        let program = command.get_program().to_string_lossy().into_owned();
        let mut process = command
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| {
                format!("cannot start {program} ({e}): install it (Debian: apt-get install ffmpeg)")
            })?;
        let (Some(mut input), Some(mut stderr)) = (process.stdin.take(), process.stderr.take())
        else {
            let _ = process.kill();
            let _ = process.wait();
            return Err(format!("{program} was started without its pipes").into());
        };
        let (frames, queue) = sync_channel::<Vec<u8>>(QUEUED_FRAMES);
        let feeder = std::thread::spawn(move || {
            for frame in queue {
                if input.write_all(&frame).is_err() {
                    return;
                }
            }
        });
        let complaints = std::thread::spawn(move || {
            let mut text = String::new();
            let _ = stderr.read_to_string(&mut text);
            text
        });
        Ok(Self {
            path,
            process,
            frames: Some(frames),
            feeder: Some(feeder),
            complaints: Some(complaints),
        })
    }

    /// Queues `frame`, waiting at most [`STALL`] for room.
    ///
    /// # Errors
    ///
    /// When the encoder has stopped reading (it ended, or stalled for [`STALL`]: it is then
    /// stopped), with what it said.
    pub(super) fn send(&mut self, frame: Vec<u8>) -> Result<(), BoxError> {
        let Some(frames) = &self.frames else {
            return Err("the encoder has already ended".into());
        };
        let refused = match send_within(frames, frame, STALL) {
            Ok(()) => return Ok(()),
            Err(refused) => refused,
        };
        let said = self.stop();
        let path = self.path.display();
        Err(match refused {
            Refused::Full => format!(
                "the encoder took no frame for {} s and was stopped; {path} is incomplete{said}",
                STALL.as_secs()
            ),
            Refused::Gone => {
                format!("the encoder stopped reading frames; {path} is incomplete{said}")
            }
        }
        .into())
    }

    /// Ends the input and waits (at most [`FINISH`]) for the encoder to write the file.
    ///
    /// # Errors
    ///
    /// When it fails, with what it said, or does not finish in time (it is then stopped).
    pub(super) fn finish(mut self) -> Result<(), BoxError> {
        self.frames = None;
        let status = poll_within(FINISH, || self.process.try_wait())?;
        let said = self.stop();
        match status {
            Some(status) if status.success() => Ok(()),
            Some(status) => Err(format!(
                "the encoder could not write {} ({status}){said}",
                self.path.display()
            )
            .into()),
            None => Err(format!(
                "the encoder did not finish {} within {} s and was stopped{said}",
                self.path.display(),
                FINISH.as_secs()
            )
            .into()),
        }
    }

    /// Kills the encoder if it still runs, reaps it and its threads; what it said, as `: …`.
    fn stop(&mut self) -> String {
        self.frames = None;
        let _already_ended = self.process.kill();
        let _reaped = self.process.wait();
        if let Some(feeder) = self.feeder.take() {
            let _ = feeder.join();
        }
        let said = self
            .complaints
            .take()
            .and_then(|complaints| complaints.join().ok())
            .unwrap_or_default();
        let said = said.trim();
        if said.is_empty() {
            String::new()
        } else {
            format!(": {said}")
        }
    }
}

impl Drop for Encoder {
    fn drop(&mut self) {
        if self.complaints.is_some() {
            self.stop();
        }
    }
}
