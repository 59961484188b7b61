//! [`Probe`]: an image a component shows of what it senses — a camera's colour and depth, a
//! tactile sensor's image — read on demand by inspectors and recorders.

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

/// The path of what a component registers under `name` (a probe, a state, a command): the
/// component's path, then the name (`/arm/state`; `/state` for the world's own).
pub(super) fn path_within(component: &str, name: &str) -> String {
    format!("{}/{name}", component.trim_end_matches('/'))
}

/// What reads a probe's image.
type ReadProbe = Box<dyn Fn() -> Result<ProbeImage, BoxError>>;

/// A named image of one component, registered with
/// [`Bind::probe`](super::Bind::probe) and listed to plugins by
/// [`World::probes`](crate::runtime::World::probes).
pub struct Probe {
    component: String,
    name: String,
    read: ReadProbe,
}

impl std::fmt::Debug for Probe {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Probe")
            .field("component", &self.component)
            .field("name", &self.name)
            .finish()
    }
}

impl Probe {
    pub(crate) fn new(component: String, name: String, read: ReadProbe) -> Self {
        Self {
            component,
            name,
            read,
        }
    }

    /// The component's path.
    pub fn component(&self) -> &str {
        &self.component
    }

    /// The probe's name within its component (`"rgb"`, `"depth"`, `"image"`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The probe's path: its component's path, then its name (`/arm/gripper/left/image`).
    pub fn path(&self) -> String {
        path_within(&self.component, &self.name)
    }

    /// The image now (a camera renders it).
    ///
    /// # Errors
    ///
    /// The component's, when it cannot make the image, naming the probe
    /// (`probe /arm/gripper/left/image: …`).
    pub fn read(&self) -> Result<ProbeImage, BoxError> {
        (self.read)().map_err(|e| format!("probe {}: {e}", self.path()).into())
    }
}
