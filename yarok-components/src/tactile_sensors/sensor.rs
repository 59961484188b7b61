//! [`TactileSensor`]: what a behaviour holds of a camera-based tactile sensor — its image,
//! the depth of what presses into its gel and what it feels — over a [`TactileFeed`], the
//! sensor in one environment.

use std::rc::Rc;

use image::RgbImage;
use yarok_core::component::{Bind, Environment};
use yarok_mjc::DepthImage;

use crate::probe_images;
#[cfg(doc)]
use crate::tactile::{default_background, elastomer::Elastomer};

/// What the sensor feels: whether something presses into the gel, how deep and over how much
/// of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Whether anything presses into the gel.
    pub in_contact: bool,
    /// The deepest indentation (metres).
    pub max_indentation: f64,
    /// The imprint's area (square metres).
    pub area: f64,
    /// The normal force (newtons) the gel is pressed with: the sum over MuJoCo's contacts
    /// between the gel and what touches it; 0 where nothing pushes (a geom placed into the gel
    /// by hand, or `mock`).
    pub force: f64,
}

/// A contact on the gel, as MuJoCo found it after the latest step: the ground truth of what the
/// sensor feels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GelContact {
    /// Where (metres) in the sensor's frame (its camera at the origin, looking along +z).
    pub position: [f64; 3],
    /// The normal force (newtons) pressing there.
    pub normal_force: f64,
}

/// A camera-based tactile sensor: `read()` gives its colour image (the sensor's optical model
/// over the depth its internal camera sees, on [`default_background`]), `read_depth()` that
/// depth (the gel's: no farther than its untouched surface), `contact()` what it feels; its
/// probes `image` and `depth` show the latest frame. Frames are made at the sensor's rate on
/// the platform's ticks: after a tick that was due a frame, `read()` returns that frame.
///
/// The gel and the housing collide with what they touch (not with the body the sensor is
/// mounted on). The internal camera sees only geoms that can touch the gel (MuJoCo's `contype`
/// and `conaffinity`): no markers, sites or visual-only meshes. Where something pushes on the
/// gel, it sinks as the sensor's [`Elastomer`] law says for the contacts' normal force: what
/// touches is shown moved into the gel along the camera's rays until its deepest point is that
/// deep (a geom placed into the gel by hand, pushing with no force, shows as placed).
///
/// In `mock` its frames are the untouched gel's; in `real` (feature `camera`) they are the
/// real sensor's camera's, with no depth. [`Digit`](super::Digit),
/// [`GelSight2014`](super::GelSight2014) and [`GelTip`](super::GelTip) deref to one.
#[derive(Clone)]
pub struct TactileSensor {
    feed: Rc<dyn TactileFeed>,
}

/// A tactile sensor could not give what was asked.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TactileError {
    /// A real sensor gives only its image: its depth, and so its contact measures, are the
    /// simulation's.
    #[error("a real tactile sensor measures no depth, only its image")]
    NoDepth,
}

/// A tactile sensor's frames in one environment: its optical model over what it senses
/// ([`Modelled`](super::modelled::Modelled), in `sim` and `mock`) or a real sensor's camera.
pub(super) trait TactileFeed {
    /// The latest frame, RGB.
    fn read(&self) -> RgbImage;
    /// The platform time of the latest frame (seconds).
    fn frame_time(&self) -> f64;
    /// See [`TactileSensor::surface_distance`].
    fn surface_distance(&self, x: f64, y: f64) -> Option<f64>;
    /// The gel's depth for the latest frame; by default none (a real sensor).
    fn read_depth(&self) -> Result<DepthImage, TactileError> {
        Err(TactileError::NoDepth)
    }
    /// What the latest frame feels; by default unknown (a real sensor).
    fn contact(&self) -> Result<Contact, TactileError> {
        Err(TactileError::NoDepth)
    }
    /// The contacts on the gel after the latest step; by default unknown (a real sensor).
    fn gel_contacts(&self) -> Result<Vec<GelContact>, TactileError> {
        Err(TactileError::NoDepth)
    }
}

impl std::fmt::Debug for TactileSensor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TactileSensor")
            .field("frame_time", &self.frame_time())
            .finish_non_exhaustive()
    }
}

impl TactileSensor {
    /// A sensor over `feed`, with the probe `image`, and `depth` where the feed has depth.
    pub(super) fn with_feed<E: Environment>(bind: &mut Bind<E>, feed: Rc<dyn TactileFeed>) -> Self {
        let sensor = Self { feed };
        let shown = sensor.clone();
        bind.probe("image", move || Ok(probe_images::rgb(shown.read())));
        if sensor.read_depth().is_ok() {
            let shown = sensor.clone();
            bind.probe("depth", move || {
                Ok(probe_images::depth(shown.read_depth()?, 1e-6))
            });
        }
        sensor
    }

    /// The latest frame, RGB.
    pub fn read(&self) -> RgbImage {
        self.feed.read()
    }

    /// The gel's depth for the latest frame (metres along the internal camera's axis): the
    /// untouched surface, and nearer where something presses into it. This is what the optical
    /// model turns into the image.
    ///
    /// # Errors
    ///
    /// [`TactileError::NoDepth`] on a real sensor.
    pub fn read_depth(&self) -> Result<DepthImage, TactileError> {
        self.feed.read_depth()
    }

    /// The platform time of the latest frame (seconds): when it was made, or when it arrived
    /// from a real sensor.
    pub fn frame_time(&self) -> f64 {
        self.feed.frame_time()
    }

    /// Where the untouched gel's outer surface is at `(x, y)` metres across the sensor's axis
    /// (its frame's x and y): its distance (metres) from the sensor's camera along the axis, or
    /// `None` where there is no gel. A press `d` metres deep at `(x, y)` puts the object's tip
    /// at `surface_distance(x, y) − d` along the axis.
    pub fn surface_distance(&self, x: f64, y: f64) -> Option<f64> {
        self.feed.surface_distance(x, y)
    }

    /// What the latest frame feels.
    ///
    /// # Errors
    ///
    /// [`TactileError::NoDepth`] on a real sensor.
    pub fn contact(&self) -> Result<Contact, TactileError> {
        self.feed.contact()
    }

    /// MuJoCo's contacts on the gel after the latest step, in the sensor's frame: where and how
    /// hard what the sensor feels touches it (none in `mock`).
    ///
    /// # Errors
    ///
    /// [`TactileError::NoDepth`] on a real sensor.
    pub fn gel_contacts(&self) -> Result<Vec<GelContact>, TactileError> {
        self.feed.gel_contacts()
    }
}
