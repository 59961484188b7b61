//! [`TactileSensor`]: a camera-based tactile sensor in the world — its internal camera renders
//! the depth of what presses into the gel, at the sensor's frame rate on the platform's ticks,
//! and an optical model turns that depth into the sensor's image.

use std::cell::RefCell;
use std::rc::Rc;

use image::RgbImage;
use yarok_core::component::{Bind, BindError, Declaration, Environment};
use yarok_core::time::Clock;
use yarok_mjc::{Body, DepthImage, Geom};
#[cfg(feature = "render")]
use yarok_mjc::{Camera, RenderPreset, Sim, SimBind};

use crate::probe_images;
use crate::tactile::calibration::Calibration;
use crate::tactile::elastomer::Elastomer;
use crate::tactile::{SizeError, default_background};

/// Indentation (metres) above which a pixel counts as touched.
const TOUCHED: f64 = 2e-5;

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

/// What the sensor senses with in `sim`: its internal camera, its gel and its body. (Built
/// without the `render` feature, a sensor has no `sim` interface, so none is made.)
#[cfg_attr(not(feature = "render"), allow(dead_code))]
pub(super) struct Sensing {
    #[cfg(feature = "render")]
    camera: Camera,
    gel: Geom,
    body: Body,
}

/// The optical side of one kind of sensor: the untouched gel as its camera sees it, and the
/// model that makes the image.
pub(super) trait Optics {
    /// The untouched gel's depth (metres along the camera axis) pixel by pixel, row-major: what
    /// the camera sees when nothing presses, and how far it sees.
    fn surface(&self) -> &[f32];
    /// The gel's thickness (metres): the deepest a press can go.
    fn thickness(&self) -> f64;
    /// The area (square metres) a pixel covers on the gel.
    fn pixel_area(&self) -> f64;
    /// How far (metres, along the sensor's axis from its camera) the untouched gel's outer
    /// surface is at `(x, y)` metres across the axis, if the gel is there.
    fn surface_distance(&self, x: f64, y: f64) -> Option<f64>;
    /// The image of the gel at `depth` (clamped to the untouched surface) over `background`.
    ///
    /// # Errors
    ///
    /// When the sizes do not match the model's.
    fn render(&mut self, depth: &[f32], background: &[u8], out: &mut [u8])
    -> Result<(), SizeError>;
    /// Splits each image's work across rayon's threads (`true`) or not.
    #[cfg(feature = "parallel")]
    fn set_parallel(&mut self, parallel: bool);
}

/// One kind of sensor: its component's declaration, image size and optics.
pub(super) trait SensorKind {
    fn declaration(&self) -> Declaration;
    /// The template's name for the gel's geom: what presses on it is what the sensor feels.
    #[cfg_attr(not(feature = "render"), allow(dead_code))]
    fn gel(&self) -> &'static str;
    /// How deep the gel sinks under a normal force.
    fn elastomer(&self) -> Elastomer;
    /// The internal camera's vertical field of view (degrees).
    fn fovy(&self) -> f64;
    /// Image columns and rows.
    fn size(&self) -> (u32, u32);
    /// Whether the real sensor's camera lies across the image: its landscape frames are turned
    /// to the image's portrait as digit-interface's `get_frame` does (transposed, then flipped
    /// upside down).
    #[cfg(feature = "camera")]
    fn turned(&self) -> bool {
        false
    }
    /// The farthest any point of the untouched gel lies from the camera (metres): nothing
    /// beyond it can show in the image.
    #[cfg_attr(not(feature = "render"), allow(dead_code))]
    fn reach(&self) -> f64;
    /// The config keys the optical model fixes (the gel's and the camera's geometry), with
    /// their values.
    fn geometry(&self) -> Vec<(&'static str, Vec<f64>)>;
    /// The calibration its `calibration = "bundled"` names, if it has one.
    fn bundled_calibration(&self) -> Option<Calibration> {
        None
    }
    /// The optics, with the gel's texture noise seeded by `seed` (none when `noise` is off):
    /// the `calibration`'s model if one is given, else the reference model.
    ///
    /// # Errors
    ///
    /// When the model cannot be made for this geometry (or calibration).
    fn optics(
        &self,
        seed: u64,
        noise: bool,
        calibration: Option<Calibration>,
    ) -> Result<Box<dyn Optics>, String>;
}

/// A camera-based tactile sensor: `read()` gives its colour image (the sensor's optical model
/// over the depth its internal camera sees, on [`default_background`]), `read_depth()` that
/// depth (the gel's: no farther than its untouched surface), `contact()` what it feels; its
///
/// The gel and the housing collide with what they touch (not with the body the sensor is
/// mounted on). The internal camera sees only geoms that can touch the gel (MuJoCo's `contype`
/// and `conaffinity`): no markers, sites or visual-only meshes. Where something pushes on the
/// gel, it sinks as the sensor's [`Elastomer`] law says for the contacts' normal force: what
/// touches is shown moved into the gel along the camera's rays until its deepest point is that
/// deep (a geom placed into the gel by hand, pushing with no force, shows as placed).
///
/// probes `image` and `depth` show the latest frame. Frames are made at the sensor's rate on the platform's
/// ticks: after a tick that was due a frame, `read()` returns that frame.
/// [`Digit`](super::Digit), [`GelSight2014`](super::GelSight2014) and
/// [`GelTip`](super::GelTip) deref to one.
#[derive(Clone)]
pub struct TactileSensor {
    feed: Feed,
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

/// Where the sensor's frames come from.
#[derive(Clone)]
enum Feed {
    /// The optical model over the internal camera's depth (`sim`), or the untouched gel
    /// (`mock`).
    Model(Rc<Inner>),
    /// The real sensor's camera.
    #[cfg(feature = "camera")]
    Real(Rc<RealSensor>),
}

#[cfg(feature = "camera")]
struct RealSensor {
    frames: Rc<crate::cameras::real::RealFrames>,
    turned: bool,
    optics: Box<dyn Optics>,
}

struct Inner {
    /// The camera, gel and body (none in `mock`).
    sensing: Option<Sensing>,
    elastomer: Elastomer,
    /// Each pixel's view direction in the sensor's frame.
    rays: Vec<[f32; 3]>,
    clock: Clock,
    period: f64,
    state: RefCell<State>,
}

struct State {
    optics: Box<dyn Optics>,
    background: Vec<u8>,
    frame: RgbImage,
    /// The gel's depth: what the camera sees, but nothing beyond the untouched gel, which is
    /// all it sees of what lies farther.
    depth: DepthImage,
    /// Platform time the next frame is due, and the latest frame's.
    due: f64,
    time: f64,
    /// The normal force on the gel at the latest frame (newtons).
    force: f64,
    failed: Option<String>,
}

impl std::fmt::Debug for TactileSensor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut debug = f.debug_struct("TactileSensor");
        match &self.feed {
            Feed::Model(inner) => debug.field("period", &inner.period),
            #[cfg(feature = "camera")]
            Feed::Real(_) => debug.field("real", &true),
        };
        debug.finish()
    }
}

impl TactileSensor {
    /// The latest frame, RGB.
    pub fn read(&self) -> RgbImage {
        match &self.feed {
            Feed::Model(inner) => inner.state.borrow().frame.clone(),
            #[cfg(feature = "camera")]
            Feed::Real(real) => {
                let frame = real.frames.latest();
                if real.turned {
                    image::imageops::rotate270(&frame)
                } else {
                    frame
                }
            }
        }
    }

    /// The gel's depth for the latest frame (metres along the internal camera's axis): the
    /// untouched surface, and nearer where something presses into it. This is what the optical
    /// model turns into the image.
    ///
    /// # Errors
    ///
    /// [`TactileError::NoDepth`] on a real sensor.
    pub fn read_depth(&self) -> Result<DepthImage, TactileError> {
        Ok(self.model()?.state.borrow().depth.clone())
    }

    /// The platform time of the latest frame (seconds): when it was made, or when it arrived
    /// from a real sensor.
    pub fn frame_time(&self) -> f64 {
        match &self.feed {
            Feed::Model(inner) => inner.state.borrow().time,
            #[cfg(feature = "camera")]
            Feed::Real(real) => real.frames.time(),
        }
    }

    /// Where the untouched gel's outer surface is at `(x, y)` metres across the sensor's axis
    /// (its frame's x and y): its distance (metres) from the sensor's camera along the axis, or
    /// `None` where there is no gel. A press `d` metres deep at `(x, y)` puts the object's tip
    /// at `surface_distance(x, y) − d` along the axis.
    pub fn surface_distance(&self, x: f64, y: f64) -> Option<f64> {
        match &self.feed {
            Feed::Model(inner) => inner.state.borrow().optics.surface_distance(x, y),
            #[cfg(feature = "camera")]
            Feed::Real(real) => real.optics.surface_distance(x, y),
        }
    }

    /// What the latest frame feels.
    ///
    /// # Errors
    ///
    /// [`TactileError::NoDepth`] on a real sensor.
    pub fn contact(&self) -> Result<Contact, TactileError> {
        let state = self.model()?.state.borrow();
        let optics = &state.optics;
        let (mut deepest, mut touched) = (0.0f64, 0usize);
        for (surface, depth) in optics.surface().iter().zip(state.depth.as_raw()) {
            let indentation =
                (f64::from(*surface) - f64::from(*depth)).clamp(0.0, optics.thickness());
            deepest = deepest.max(indentation);
            touched += usize::from(indentation > TOUCHED);
        }
        Ok(Contact {
            in_contact: touched > 0,
            max_indentation: deepest,
            area: touched as f64 * optics.pixel_area(),
            force: state.force,
        })
    }

    /// MuJoCo's contacts on the gel after the latest step, in the sensor's frame: where and how
    /// hard what the sensor feels touches it (none in `mock`).
    ///
    /// # Errors
    ///
    /// [`TactileError::NoDepth`] on a real sensor.
    pub fn gel_contacts(&self) -> Result<Vec<GelContact>, TactileError> {
        let Some(sensing) = &self.model()?.sensing else {
            return Ok(Vec::new());
        };
        let pose = sensing.body.pose();
        Ok(sensing
            .gel
            .contacts()
            .into_iter()
            .map(|contact| GelContact {
                position: pose.to_local(contact.position),
                normal_force: contact.normal_force,
            })
            .collect())
    }

    /// The optical model's side, which a real sensor does not have.
    fn model(&self) -> Result<&Inner, TactileError> {
        match &self.feed {
            Feed::Model(inner) => Ok(inner),
            #[cfg(feature = "camera")]
            Feed::Real(_) => Err(TactileError::NoDepth),
        }
    }

    #[cfg(feature = "render")]
    /// Binds a sensor of `kind` in `sim`: its internal camera renders depth with the depth
    /// preset, only of geoms that can touch the gel and can reach it.
    pub(super) fn bind_sim(kind: &dyn SensorKind, bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let (width, height) = kind.size();
        let gel = bind.geom(kind.gel())?;
        let camera = bind
            .camera_with("camera", width, height, RenderPreset::Depth)?
            .touching(&gel)
            .within(kind.reach());
        let body = bind.body("sensor")?;
        Self::bind(kind, bind, Some(Sensing { camera, gel, body }))
    }

    /// Binds a sensor of `kind` that senses with `sensing` (none in `mock`: its frame is the
    /// untouched gel).
    pub(super) fn bind<E: Environment>(
        kind: &dyn SensorKind,
        bind: &mut Bind<E>,
        sensing: Option<Sensing>,
    ) -> Result<Self, BindError> {
        let fps = frame_rate(bind)?;
        check_geometry(kind, bind)?;
        let noise: bool = bind.config_value("noise")?;
        let parallel: bool = bind.config_value("parallel")?;
        let calibration = calibration(kind, bind)?;
        #[cfg_attr(not(feature = "parallel"), expect(unused_mut))]
        let mut optics = kind
            .optics(bind.seed(), noise, calibration)
            .map_err(|e| bind.error(e))?;
        #[cfg(feature = "parallel")]
        optics.set_parallel(parallel);
        if parallel && !cfg!(feature = "parallel") {
            return Err(bind.error(
                "parallel = true needs yarok-components' `parallel` feature, which is off",
            ));
        }
        let (width, height) = kind.size();
        let background = default_background(width as usize, height as usize);
        let untouched = DepthImage::from_fn(width, height, |x, y| {
            image::Luma([optics.surface()[(y * width + x) as usize]])
        });
        let inner = Rc::new(Inner {
            sensing,
            elastomer: kind.elastomer(),
            rays: pixel_rays(width, height, kind.fovy()),
            clock: bind.clock(),
            period: 1.0 / fps,
            state: RefCell::new(State {
                optics,
                frame: RgbImage::new(width, height),
                background,
                depth: untouched,
                due: 0.0,
                time: 0.0,
                force: 0.0,
                failed: None,
            }),
        });
        inner.frame(inner.clock.time(), true);
        if let Some(error) = inner.state.borrow_mut().failed.take() {
            return Err(bind.error(error));
        }
        let sensor = Self {
            feed: Feed::Model(Rc::clone(&inner)),
        };
        sensor.show_image(bind);
        let shown = sensor.clone();
        bind.probe("depth", move || {
            Ok(probe_images::depth(shown.read_depth()?, 1e-6))
        });
        // The world went back to its start: a frame of it now, and the frames' schedule anew.
        let restarting = Rc::clone(&inner);
        bind.on_restart(move || restarting.frame(restarting.clock.time(), true));
        let ticking = Rc::clone(&inner);
        bind.on_tick(move || {
            ticking.frame(ticking.clock.time(), false);
            match ticking.state.borrow_mut().failed.take() {
                Some(error) => Err(error.into()),
                None => Ok(()),
            }
        });
        Ok(sensor)
    }
}

impl TactileSensor {
    /// Binds a real sensor of `kind`: its camera's frames (a Video4Linux2 device, or an MJPEG
    /// stream, as [`Cam`](crate::cameras::Cam)'s `real` interface takes them), at the kind's
    /// size (across, when [`SensorKind::turned`]) and the configured rate.
    #[cfg(feature = "camera")]
    pub(super) async fn bind_real(
        kind: &dyn SensorKind,
        bind: &mut Bind<yarok_hw::Real>,
    ) -> Result<Self, BindError> {
        let fps = frame_rate(bind)?;
        check_geometry(kind, bind)?;
        let (width, height) = kind.size();
        let turned = kind.turned();
        let (across, down) = if turned {
            (height, width)
        } else {
            (width, height)
        };
        let rate = fps.round().clamp(1.0, f64::from(u32::MAX)) as u32;
        let frames = crate::cameras::real::bind_frames(bind, across, down, rate).await?;
        let optics = kind
            .optics(bind.seed(), false, None)
            .map_err(|e| bind.error(e))?;
        let sensor = Self {
            feed: Feed::Real(Rc::new(RealSensor {
                frames,
                turned,
                optics,
            })),
        };
        sensor.show_image(bind);
        Ok(sensor)
    }

    /// Registers the probe `image`.
    fn show_image<E: Environment>(&self, bind: &mut Bind<E>) {
        let shown = self.clone();
        bind.probe("image", move || Ok(probe_images::rgb(shown.read())));
    }
}

/// The configured frame rate, a positive number.
fn frame_rate<E: Environment>(bind: &Bind<E>) -> Result<f64, BindError> {
    let fps: f64 = bind.config_value("fps")?;
    if !(fps > 0.0 && fps.is_finite()) {
        return Err(bind.error(format!("fps must be a positive number, not {fps}")));
    }
    Ok(fps)
}

/// The calibration the config's `calibration` names: `"none"` (the reference model),
/// `"bundled"` (the kind's own) or a calibration file.
fn calibration<E: Environment>(
    kind: &dyn SensorKind,
    bind: &Bind<E>,
) -> Result<Option<Calibration>, BindError> {
    let named: String = bind.config_value("calibration")?;
    match named.as_str() {
        "none" => Ok(None),
        "bundled" => kind.bundled_calibration().map(Some).ok_or_else(|| {
            bind.error("calibration = \"bundled\", but this sensor has no bundled calibration")
        }),
        path => Calibration::load(path)
            .map(Some)
            .map_err(|e| bind.error(format!("calibration = {path:?}: {e}"))),
    }
}

/// Refuses config that changes the geometry the optical model is made for.
fn check_geometry<E: Environment>(kind: &dyn SensorKind, bind: &Bind<E>) -> Result<(), BindError> {
    for (key, fixed) in kind.geometry() {
        let set: Vec<f64> = match fixed.len() {
            1 => vec![bind.config_value::<f64>(key)?],
            _ => bind.config_value(key)?,
        };
        let same = set.len() == fixed.len()
            && set
                .iter()
                .zip(&fixed)
                .all(|(set, fixed)| (set - fixed).abs() <= 1e-12 * fixed.abs().max(1.0));
        if !same {
            return Err(bind.error(format!(
                "{key} = {set:?}, but the optical model is made for {fixed:?}: the gel's and the \
                 camera's geometry cannot be changed"
            )));
        }
    }
    Ok(())
}

impl Inner {
    /// The normal force on the gel (newtons) and the direction it pushes the gel in (a unit
    /// vector in the sensor's frame; the force-weighted mean of the contacts' normals).
    fn push(&self) -> (f64, [f64; 3]) {
        let Some(sensing) = &self.sensing else {
            return (0.0, [0.0, 0.0, -1.0]);
        };
        let pose = sensing.body.pose();
        let origin = pose.to_local([0.0; 3]);
        let (mut force, mut sum) = (0.0, [0.0; 3]);
        for contact in sensing.gel.contacts() {
            let pushing = contact.normal_force.max(0.0);
            // The normal points from the gel to what touches it; the push is the other way.
            let normal = pose.to_local(contact.normal.map(|n| -n));
            force += pushing;
            for axis in 0..3 {
                sum[axis] += pushing * (normal[axis] - origin[axis]);
            }
        }
        let norm = sum.iter().map(|s| s * s).sum::<f64>().sqrt();
        if norm > 0.0 {
            (force, sum.map(|s| s / norm))
        } else {
            (force, [0.0, 0.0, -1.0])
        }
    }

    /// Makes a frame if one is due at platform time `now` (or `force`d).
    fn frame(&self, now: f64, force: bool) {
        let mut state = self.state.borrow_mut();
        if !force && now + 1e-9 < state.due {
            return;
        }
        state.due = now + self.period;
        state.time = now;
        #[cfg(feature = "render")]
        if let Some(sensing) = &self.sensing
            && let Err(error) = sensing.camera.depth_into(&mut state.depth)
        {
            state.failed = Some(error.to_string());
            return;
        }
        let (force, push) = self.push();
        state.force = force;
        let State {
            optics,
            background,
            frame,
            depth,
            failed,
            ..
        } = &mut *state;
        sink(
            self.elastomer.indentation(force),
            push,
            &self.rays,
            optics.surface(),
            depth,
        );
        if let Err(error) = optics.render(depth, background, frame) {
            *failed = Some(error.to_string());
        }
    }
}

/// Moves what `depth` shows along `push` (a unit vector in the sensor's frame, into the gel) so
/// that it presses `indentation` metres into the gel (measured along `push`) whose untouched
/// `surface` is given, then clamps the depth to that surface. Nothing moves when it already
/// presses as deep (placed there by hand) or the gel feels no force. `rays` are the pixels'
/// unit view directions.
fn sink(indentation: f64, push: [f64; 3], rays: &[[f32; 3]], surface: &[f32], depth: &mut [f32]) {
    // How much nearer (along the camera's axis) a point seen along `ray` comes per metre of
    // motion along `push`, for a surface facing the push (a ray grazing it is held at 5×).
    let approach = |ray: &[f32; 3]| {
        let facing = -(f64::from(ray[0]) * push[0]
            + f64::from(ray[1]) * push[1]
            + f64::from(ray[2]) * push[2]);
        (f64::from(ray[2]) / facing.max(0.2)) as f32
    };
    if indentation > 0.0 {
        let approaches: Vec<f32> = rays.iter().map(approach).collect();
        let deepest = approaches
            .iter()
            .zip(surface.iter().zip(depth.iter()))
            .map(|(approach, (surface, depth))| (surface - depth) / approach)
            .fold(0.0f32, f32::max);
        let shift = (indentation as f32 - deepest).max(0.0);
        if shift > 0.0 {
            for (approach, depth) in approaches.iter().zip(depth.iter_mut()) {
                *depth -= shift * approach;
            }
        }
    }
    for (depth, surface) in depth.iter_mut().zip(surface) {
        *depth = depth.min(*surface);
    }
}

/// The unit view direction of each pixel of a `width × height` image with a vertical field of
/// `fovy` degrees, in the sensor's frame (the camera at its origin looking along +z, image
/// right along +x and down along +y), row-major.
fn pixel_rays(width: u32, height: u32, fovy: f64) -> Vec<[f32; 3]> {
    let focal = f64::from(height) / 2.0 / (fovy.to_radians() / 2.0).tan();
    let (cx, cy) = (f64::from(width) / 2.0, f64::from(height) / 2.0);
    (0..height)
        .flat_map(|v| (0..width).map(move |u| (u, v)))
        .map(|(u, v)| {
            let ray = [
                (f64::from(u) + 0.5 - cx) / focal,
                (f64::from(v) + 0.5 - cy) / focal,
                1.0,
            ];
            let norm = ray.iter().map(|r| r * r).sum::<f64>().sqrt();
            ray.map(|r| (r / norm) as f32)
        })
        .collect()
}

/// A component newtype over [`TactileSensor`] for one [`SensorKind`]: `sim` and `mock`
/// interfaces, and `real` with the `camera` feature.
macro_rules! tactile_sensor_component {
    ($(#[$doc:meta])* $name:ident, $kind:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone)]
        pub struct $name(TactileSensor);

        impl std::ops::Deref for $name {
            type Target = TactileSensor;

            fn deref(&self) -> &TactileSensor {
                &self.0
            }
        }

        impl yarok_core::component::Component for $name {
            fn declaration() -> yarok_core::component::Declaration {
                SensorKind::declaration(&$kind)
            }

            fn interfaces(interfaces: &mut yarok_core::component::Interfaces<Self>) {
                #[cfg(feature = "render")]
                interfaces.add::<yarok_mjc::Sim>();
                #[cfg(not(feature = "render"))]
                interfaces.unavailable::<yarok_mjc::Sim>("the `render` feature");
                interfaces.add::<yarok_core::component::Mock>();
                #[cfg(feature = "camera")]
                interfaces.add::<yarok_hw::Real>();
                #[cfg(not(feature = "camera"))]
                interfaces.unavailable::<yarok_hw::Real>("the `camera` feature");
            }
        }

        #[cfg(feature = "camera")]
        impl yarok_core::component::Interface<yarok_hw::Real> for $name {
            fn check(
                bind: &yarok_core::component::Bind<yarok_hw::Real>,
            ) -> Result<(), yarok_core::component::BindError> {
                crate::cameras::real::check_settings(bind)
            }

            async fn bind(
                bind: &mut yarok_core::component::Bind<yarok_hw::Real>,
            ) -> Result<Self, yarok_core::component::BindError> {
                TactileSensor::bind_real(&$kind, bind).await.map($name)
            }
        }

        #[cfg(feature = "render")]
        impl yarok_core::component::Interface<yarok_mjc::Sim> for $name {
            async fn bind(
                bind: &mut yarok_core::component::Bind<yarok_mjc::Sim>,
            ) -> Result<Self, yarok_core::component::BindError> {
                TactileSensor::bind_sim(&$kind, bind).map($name)
            }
        }

        impl yarok_core::component::Interface<yarok_core::component::Mock> for $name {
            async fn bind(
                bind: &mut yarok_core::component::Bind<yarok_core::component::Mock>,
            ) -> Result<Self, yarok_core::component::BindError> {
                TactileSensor::bind(&$kind, bind, None).map($name)
            }
        }
    };
}

pub(super) use tactile_sensor_component;
