//! A tactile sensor in `real`: the frames of the sensor's own camera.

use std::rc::Rc;

use image::RgbImage;
use yarok_core::component::{Bind, BindError};

use super::kind::{Optics, SensorConfig, SensorKind};
use super::sensor::{TactileFeed, TactileSensor};
use crate::cameras::real::{RealFrames, bind_frames};

/// A real sensor's camera, and its optics for the gel's geometry.
struct RealSensor {
    frames: Rc<RealFrames>,
    /// Whether the camera lies across the image (see [`SensorKind::turned`]).
    turned: bool,
    optics: Box<dyn Optics>,
}

impl TactileFeed for RealSensor {
    fn read(&self) -> RgbImage {
        let frame = self.frames.latest();
        if self.turned {
            image::imageops::rotate270(&frame)
        } else {
            frame
        }
    }

    fn frame_time(&self) -> f64 {
        self.frames.time()
    }

    fn surface_distance(&self, x: f64, y: f64) -> Option<f64> {
        self.optics.surface_distance(x, y)
    }
}

impl TactileSensor {
    /// Binds a real sensor of `kind`: its camera's frames (a Video4Linux2 device, or an MJPEG
    /// stream, as [`Cam`](crate::cameras::Cam)'s `real` interface takes them), at the kind's
    /// size (across, when [`SensorKind::turned`]) and the configured rate.
    pub(super) async fn bind_real(
        kind: &dyn SensorKind,
        bind: &mut Bind<yarok_hw::Real>,
    ) -> Result<Self, BindError> {
        let fps = bind.config::<SensorConfig>()?.frame_rate(bind)?;
        let (width, height) = kind.size();
        let turned = kind.turned();
        let (across, down) = if turned {
            (height, width)
        } else {
            (width, height)
        };
        let rate = fps.round().clamp(1.0, f64::from(u32::MAX)) as u32;
        let frames = bind_frames(bind, across, down, rate).await?;
        let optics = kind
            .optics(bind.seed(), false, None)
            .map_err(|e| bind.error(e))?;
        let feed = Rc::new(RealSensor {
            frames,
            turned,
            optics,
        });
        Ok(Self::with_feed(bind, feed))
    }
}
