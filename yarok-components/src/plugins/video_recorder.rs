//! [`VideoRecorder`]: a camera of the model filmed to an MP4 file through `ffmpeg`.

use std::path::PathBuf;

use yarok_core::BoxError;
use yarok_core::runtime::{Plugin, World};
use yarok_mjc::SimBackend;

use super::encoder::{Encoder, H264};
use crate::model_cameras::ModelCameras;

/// What a [`VideoRecorder`] films (`[plugins.video]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VideoRecorderSettings {
    /// The video file (MP4 whatever its extension; a file there is replaced only if yarok
    /// encoded it).
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
/// `PATH`) and waits for at the end. An encoder that stops taking frames for 5 s ends the run
/// with an error, and is stopped; it is never left running.
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

/// The camera, with its renderer, and the encoder being fed.
#[derive(Debug)]
struct Filming {
    camera: ModelCameras,
    encoder: Encoder,
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

    /// The H.264 video the settings ask for.
    fn video(&self) -> H264 {
        H264 {
            size: self.settings.size,
            fps: self.settings.fps,
            keyframe_interval: None,
            crf: None,
        }
    }

    /// Ends the video: the encoder reads to the end of its input and writes the file.
    fn finish(&mut self) -> Result<(), BoxError> {
        match self.filming.take() {
            Some(filming) => filming.encoder.finish(),
            None => Ok(()),
        }
    }
}

impl Plugin for VideoRecorder {
    fn writes(&self) -> Vec<std::path::PathBuf> {
        vec![self.settings.path.clone()]
    }

    fn name(&self) -> String {
        format!("video ({})", self.settings.path.display())
    }

    fn environments(&self) -> Vec<&'static str> {
        super::only_sim()
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let sim = super::sim_backend(world)?;
        let settings = &self.settings;
        let camera = ModelCameras::find(
            sim,
            std::slice::from_ref(&settings.camera),
            settings.size,
            settings.quality,
        )?;
        let encoder = Encoder::start(&self.video(), self.settings.path.clone())?;
        self.filming = Some(Filming { camera, encoder });
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
        for frame in filming.camera.render(sim)? {
            let sent = filming.encoder.send(frame);
            if sent.is_err() {
                self.filming = None;
                return sent;
            }
        }
        Ok(())
    }

    fn end(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        self.finish()
    }
}
