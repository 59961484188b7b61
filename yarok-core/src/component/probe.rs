//! [`Probe`]: an image a component shows of what it senses — a camera's colour and depth, a
//! tactile sensor's image — read on demand by inspectors and recorders.

use super::Named;
use crate::BoxError;

/// An image a probe shows, top row first.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ProbeImage {
    /// Colour: `3 · width · height` bytes, RGB.
    Rgb {
        /// Columns.
        width: u32,
        /// Rows.
        height: u32,
        /// The pixels, RGB interleaved.
        pixels: Vec<u8>,
    },
    /// Depth: `width · height` distances in metres.
    Depth {
        /// Columns.
        width: u32,
        /// Rows.
        height: u32,
        /// The distances.
        metres: Vec<f32>,
        /// The distance (metres) one count stands for where the depth is written as 16-bit
        /// integers (a PNG): the finest the probe's range allows — a tactile sensor's 1 µm (up to
        /// 65.5 mm), a camera's 1 mm (up to 65.5 m).
        unit: f32,
    },
}

impl ProbeImage {
    /// Columns and rows.
    pub fn size(&self) -> (u32, u32) {
        match self {
            ProbeImage::Rgb { width, height, .. } | ProbeImage::Depth { width, height, .. } => {
                (*width, *height)
            }
        }
    }
}

/// A named image of one component, registered with [`Bind::probe`](super::Bind::probe) and
/// listed to plugins by [`World::probes`](crate::runtime::World::probes).
pub type Probe = Named<dyn Fn() -> Result<ProbeImage, BoxError>>;

impl Probe {
    /// The image now (a camera renders it).
    ///
    /// # Errors
    ///
    /// The component's, when it cannot make the image, naming the probe
    /// (`probe /arm/gripper/left/image: …`).
    pub fn read(&self) -> Result<ProbeImage, BoxError> {
        (self.function())().map_err(|e| format!("probe {}: {e}", self.path()).into())
    }
}
