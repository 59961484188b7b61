//! [`Encoder`]: an `ffmpeg` process fed raw frames from a thread of its own, every wait on it
//! bounded: an encoder that stops reading ends the run with an error instead of blocking it.

use std::io::{Read, Seek, Write};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{SyncSender, sync_channel};
use std::thread::JoinHandle;
use std::time::Duration;

use yarok_core::BoxError;
use yarok_core::output_file::OutputFile;

use super::bounded_wait::{Refused, poll_within, send_within};

/// Frames queued for the encoder before the platform waits for it.
const QUEUED_FRAMES: usize = 8;

/// How long the encoder may take no frame before it is taken as stalled.
const STALL: Duration = Duration::from_secs(5);

/// How long the encoder may take to write the file once its input has ended.
const FINISH: Duration = Duration::from_secs(60);

/// The comment every video yarok encodes carries (with yarok's version): how an existing file
/// is known as yarok's.
const WRITTEN_BY: &str = "written by yarok";

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
    fn ffmpeg(&self, path: &std::path::Path) -> Command {
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
        command
            .args([
                "-metadata",
                &format!("comment={WRITTEN_BY} {}", env!("CARGO_PKG_VERSION")),
            ])
            .args(["-movflags", "+faststart", "-f", "mp4"])
            .arg(path);
        command
    }
}

/// An encoder process writing `path` from the frames it is sent ([`OutputFile`]: beside the
/// path, put in its place when finished); killed and reaped when dropped unfinished.
#[derive(Debug)]
pub(super) struct Encoder {
    path: PathBuf,
    output: Option<OutputFile>,
    process: Child,
    frames: Option<SyncSender<Vec<u8>>>,
    feeder: Option<JoinHandle<()>>,
    complaints: Option<JoinHandle<String>>,
}

impl Encoder {
    /// Starts ffmpeg encoding `video` to `path` from the raw frames it is sent.
    ///
    /// # Errors
    ///
    /// When `path` holds a file yarok did not encode (it is left as it is), or the program
    /// cannot be started.
    pub(super) fn start(video: &H264, path: PathBuf) -> Result<Self, BoxError> {
        let output = OutputFile::create(&path, "video", encoded_by_yarok)?;
        let mut command = video.ffmpeg(output.writing_path());
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
            output: Some(output),
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
        if let Some(output) = self.output.take() {
            output.commit()?;
        }
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

    /// Ends the input and waits (at most [`FINISH`]) for the encoder to write the file, then
    /// checks that the file is a whole MP4 and puts it at its path (an incomplete one too,
    /// named so in the error: what was encoded is kept).
    ///
    /// # Errors
    ///
    /// When it fails or reports an error, with what it said; when it does not finish in time
    /// (it is then stopped); when the file it left is not whole.
    pub(super) fn finish(mut self) -> Result<(), BoxError> {
        self.frames = None;
        let status = poll_within(FINISH, || self.process.try_wait())?;
        let said = self.stop();
        let Some(output) = self.output.take() else {
            return Err("the encoder has already ended".into());
        };
        let whole = whole_mp4(output.writing_path());
        output.commit()?;
        let path = self.path.display();
        match status {
            // ffmpeg exits 0 when writing the index at the end fails (a disk that fills then):
            // at `-loglevel error` anything it says is an error.
            Some(status) if status.success() && said.is_empty() => {
                whole.map_err(|why| format!("{path} is incomplete: {why}").into())
            }
            Some(status) if status.success() => {
                Err(format!("the encoder failed writing {path}; it is incomplete{said}").into())
            }
            Some(status) => Err(format!(
                "the encoder could not write {path} ({status}); it is incomplete{said}"
            )
            .into()),
            None => Err(format!(
                "the encoder did not finish {path} within {} s and was stopped{said}",
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

/// An MP4 file's top-level box: its kind, and where it starts and ends (bytes).
struct Mp4Box {
    kind: [u8; 4],
    start: u64,
    end: u64,
}

/// The top-level box at byte `at` of `file`, `length` bytes long, read from its header alone.
fn box_at(file: &mut std::fs::File, at: u64, length: u64) -> Result<Mp4Box, String> {
    let mut header = [0u8; 16];
    let available = usize::try_from(length.saturating_sub(at).min(16)).unwrap_or(16);
    if available < 8 {
        return Err("it ends inside a box's header".into());
    }
    file.seek(std::io::SeekFrom::Start(at))
        .and_then(|_| file.read_exact(&mut header[..available]))
        .map_err(|e| format!("cannot read it back ({e})"))?;
    let kind = [header[4], header[5], header[6], header[7]];
    let size = match u32::from_be_bytes([header[0], header[1], header[2], header[3]]) {
        0 => length - at,
        1 if available < 16 => return Err("it ends inside a box's size".into()),
        1 => u64::from_be_bytes(header[8..16].try_into().unwrap_or_default()),
        size => u64::from(size),
    };
    match at.checked_add(size) {
        Some(end) if size >= 8 && end <= length => Ok(Mp4Box {
            kind,
            start: at,
            end,
        }),
        _ => Err(format!(
            "its box {:?} at byte {at} runs past the file's end ({length} bytes)",
            String::from_utf8_lossy(&kind)
        )),
    }
}

/// `path` opened, with its length.
fn opened(path: &std::path::Path) -> std::io::Result<(std::fs::File, u64)> {
    let file = std::fs::File::open(path)?;
    let length = file.metadata()?.len();
    Ok((file, length))
}

/// Whether the file at `path` is a video yarok encoded: an MP4 whose index holds yarok's
/// comment (the index comes first: [`H264::ffmpeg`] asks for it at the front).
fn encoded_by_yarok(path: &std::path::Path) -> std::io::Result<bool> {
    let (mut file, length) = opened(path)?;
    let mut at = 0;
    // The boxes before the index (ftyp, free) are small; a file whose index is not within the
    // first few boxes is not one of ours.
    for _ in 0..4 {
        let Ok(found) = box_at(&mut file, at, length) else {
            return Ok(false);
        };
        if &found.kind == b"moov" {
            let mut index = Vec::new();
            Read::by_ref(&mut file)
                .take((found.end - found.start).min(64 << 20))
                .read_to_end(&mut index)?;
            let mark = WRITTEN_BY.as_bytes();
            return Ok(index.windows(mark.len()).any(|w| w == mark));
        }
        at = found.end;
    }
    Ok(false)
}

/// Checks that `path` is whole as an MP4 file: its top-level boxes follow one another to the
/// file's end exactly, and one of them is the index (`moov`) players need. Only the boxes'
/// headers are read.
fn whole_mp4(path: &std::path::Path) -> Result<(), String> {
    let (mut file, length) = opened(path).map_err(|e| format!("cannot read it back ({e})"))?;
    let mut at = 0;
    let mut index = false;
    while at < length {
        let found = box_at(&mut file, at, length)?;
        index |= &found.kind == b"moov";
        at = found.end;
    }
    if index {
        Ok(())
    } else {
        Err("it has no index (moov box): players cannot open it".into())
    }
}

impl Drop for Encoder {
    fn drop(&mut self) {
        if self.complaints.is_some() {
            self.stop();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Encoder, H264, whole_mp4};

    /// ffmpeg's MP4 of 30 grey frames is whole; cut anywhere, it is not, and the reason says
    /// where.
    #[test]
    fn an_mp4_cut_short_is_not_whole() {
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("grey.mp4");
        let video = H264 {
            size: [32, 16],
            fps: 30.0,
            keyframe_interval: None,
            crf: None,
        };
        let mut encoder = Encoder::start(&video, path.clone()).unwrap();
        for level in 0..30u8 {
            encoder.send(vec![level * 8; 32 * 16 * 3]).unwrap();
        }
        encoder.finish().unwrap();
        let bytes = std::fs::read(&path).unwrap();
        for cut in [4, 100, bytes.len() / 2, bytes.len() - 1] {
            std::fs::write(&path, &bytes[..cut]).unwrap();
            let why = whole_mp4(&path).unwrap_err();
            assert!(
                why.contains("past the file's end") || why.contains("inside a box"),
                "{cut}: {why}"
            );
        }
        std::fs::write(&path, &bytes[..32]).unwrap();
        assert!(whole_mp4(&path).unwrap_err().contains("no index"));
    }
}
