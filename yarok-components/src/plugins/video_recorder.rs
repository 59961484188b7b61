//! [`VideoRecorder`]: a camera of the model filmed to an MP4 file through `ffmpeg`.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Child, ChildStdin, Command, Stdio};

use yarok_core::BoxError;
use yarok_core::runtime::{Plugin, World};
use yarok_mjc::{CameraId, Renderer, SimBackend};

use super::preset;

/// What a [`VideoRecorder`] films (`[plugins.video]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VideoRecorderSettings {
    /// The video file (`.mp4`; overwritten).
    pub path: PathBuf,
    /// The model's camera to film, by name.
    pub camera: String,
    /// Frames a second, of platform time: the video plays at the simulation's speed.
    pub fps: f64,
    /// Width and height (even numbers, as H.264 needs).
    pub size: [u32; 2],
    /// Render with MuJoCo's shadows, reflections and multisampling, several times slower on a
    /// CPU renderer (default: without).
    pub quality: bool,
}

impl Default for VideoRecorderSettings {
    fn default() -> Self {
        Self {
            path: PathBuf::from("run.mp4"),
            camera: "overview".into(),
            fps: 30.0,
            size: [640, 480],
            quality: false,
        }
    }
}

/// Films a camera of the model in `sim` to an H.264 MP4 file for sharing, a frame every
/// `1 / fps` seconds of platform time, through an `ffmpeg` process it starts (found on the
/// `PATH`) and waits for at the end.
///
/// Registered by `yarok::platform()` as `video`:
///
/// ```toml
/// [plugins.video]
/// path = "pick_and_place.mp4"
/// camera = "overview"
/// ```
#[derive(Debug)]
pub struct VideoRecorder {
    settings: VideoRecorderSettings,
    filming: Option<Filming>,
    next_frame: f64,
}

/// The camera, its renderer and the encoder being fed.
struct Filming {
    camera: CameraId,
    renderer: Renderer,
    ffmpeg: Child,
    frames: ChildStdin,
}

impl std::fmt::Debug for Filming {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Filming")
            .field("camera", &self.camera)
            .field("ffmpeg", &self.ffmpeg.id())
            .finish()
    }
}

impl VideoRecorder {
    /// A recorder with these settings; `ffmpeg` starts when the run does.
    ///
    /// # Errors
    ///
    /// When `fps` is not a positive number or the size is not even and positive.
    pub fn new(settings: VideoRecorderSettings) -> Result<Self, BoxError> {
        if !(settings.fps > 0.0 && settings.fps.is_finite()) {
            return Err(format!("`fps` {} must be above 0", settings.fps).into());
        }
        if settings.size.iter().any(|s| *s == 0 || s % 2 == 1) {
            return Err(format!("`size` {:?} must be even numbers above 0", settings.size).into());
        }
        Ok(Self {
            settings,
            filming: None,
            next_frame: 0.0,
        })
    }

    fn ffmpeg(&self) -> Result<Child, BoxError> {
        let [width, height] = self.settings.size;
        Command::new("ffmpeg")
            .args([
                "-loglevel",
                "error",
                "-y",
                "-f",
                "rawvideo",
                "-pix_fmt",
                "rgb24",
            ])
            .args(["-s", &format!("{width}x{height}")])
            .args(["-r", &self.settings.fps.to_string(), "-i", "-"])
            .args([
                "-c:v",
                "libx264",
                "-pix_fmt",
                "yuv420p",
                "-movflags",
                "+faststart",
            ])
            .arg(&self.settings.path)
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| {
                format!("cannot start ffmpeg ({e}): install it (Debian: apt-get install ffmpeg)")
                    .into()
            })
    }

    /// Ends the video: the encoder reads to the end of its input and writes the file.
    fn finish(&mut self) -> Result<(), BoxError> {
        let Some(Filming { ffmpeg, frames, .. }) = self.filming.take() else {
            return Ok(());
        };
        drop(frames);
        let output = ffmpeg.wait_with_output()?;
        if !output.status.success() {
            return Err(format!(
                "ffmpeg could not write {}: {}",
                self.settings.path.display(),
                String::from_utf8_lossy(&output.stderr).trim()
            )
            .into());
        }
        Ok(())
    }
}

impl Plugin for VideoRecorder {
    fn writes(&self) -> Vec<std::path::PathBuf> {
        vec![self.settings.path.clone()]
    }

    fn name(&self) -> String {
        format!("video ({})", self.settings.path.display())
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let sim = world.backend::<SimBackend>().ok_or_else(|| {
            format!(
                "films the model's cameras in `sim`, not in `{}`",
                world.pl().environment()
            )
        })?;
        let camera = sim
            .model()
            .camera(&self.settings.camera)
            .map_err(|e| format!("camera to film: {e}"))?;
        let [width, height] = self.settings.size;
        let renderer = Renderer::builder()
            .size(width, height)
            .preset(preset(self.settings.quality))
            .build(sim.model())?;
        let mut ffmpeg = self.ffmpeg()?;
        let frames = ffmpeg.stdin.take().ok_or("ffmpeg has no input")?;
        self.filming = Some(Filming {
            camera,
            renderer,
            ffmpeg,
            frames,
        });
        Ok(())
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let (Some(sim), Some(filming)) = (world.backend::<SimBackend>(), &mut self.filming) else {
            return Ok(());
        };
        let time = sim.data().time();
        if time + 1e-9 < self.next_frame {
            return Ok(());
        }
        self.next_frame += 1.0 / self.settings.fps;
        let frame = filming
            .renderer
            .render_rgb(&mut sim.data_mut(), filming.camera)?;
        if filming.frames.write_all(frame.as_raw()).is_err() {
            // ffmpeg ended early: say why.
            self.finish()?;
            return Err("ffmpeg stopped reading frames".into());
        }
        Ok(())
    }

    fn end(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        self.finish()
    }
}

impl Drop for VideoRecorder {
    fn drop(&mut self) {
        if let Some(filming) = &mut self.filming {
            let _already_ended = filming.ffmpeg.kill();
            let _reaped = filming.ffmpeg.wait();
        }
    }
}
