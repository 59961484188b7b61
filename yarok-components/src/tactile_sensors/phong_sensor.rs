//! [`PhongSensor`]: a camera-based tactile sensor in the world (DIGIT, GelSight), its image from
//! the Phong optical model over the depth its internal camera renders, at the sensor's frame
//! rate.

use std::cell::RefCell;
use std::rc::Rc;

use image::RgbImage;
use yarok_core::component::{Bind, BindError, Declaration, Environment};
use yarok_core::time::Clock;
use yarok_mjc::{Camera, DepthImage, RenderPreset, Sim, SimBind};

use crate::tactile::default_background;
use crate::tactile::phong::{PhongModel, PhongParams};

/// What makes one sensor of the kind: its image, its gel and camera, its model and rate.
#[derive(Debug, Clone, Copy)]
pub(super) struct Spec {
    pub(super) tag: &'static str,
    /// Image columns and rows.
    pub(super) width: u32,
    pub(super) height: u32,
    /// Distance from the camera to the gel's outer face, and the gel's thickness (metres).
    pub(super) gel_face: f64,
    pub(super) thickness: f64,
    /// Half sizes (x, y) of the housing and of the gel (metres).
    pub(super) housing: [f64; 2],
    pub(super) gel: [f64; 2],
    /// The optical model's parameters (lights, metres per pixel, …); its depths are set from
    /// `gel_face` and `thickness`.
    pub(super) model: fn() -> PhongParams,
    /// Frames per second by default: the real sensor's.
    pub(super) fps: f64,
}

impl Spec {
    /// The optical model's parameters for this geometry.
    fn params(&self) -> PhongParams {
        PhongParams {
            elastomer_thickness: self.thickness,
            min_depth: self.gel_face - self.thickness,
            ..(self.model)()
        }
    }

    /// The camera's vertical field of view (degrees) that spans the model's image at the gel.
    fn fovy(&self) -> f64 {
        let half = f64::from(self.height) / 2.0 * self.params().px2m_ratio;
        2.0 * (half / self.gel_face).atan().to_degrees()
    }

    /// The component's declaration: the shared template with this sensor's geometry.
    pub(super) fn declaration(&self) -> Declaration {
        Declaration::new(self.tag)
            .default("pos", [0.0; 3])
            .default("quat", [1.0, 0.0, 0.0, 0.0])
            .default("fps", self.fps)
            .default("noise", true)
            .default("gel_face", self.gel_face)
            .default("thickness", self.thickness)
            .default("housing", self.housing)
            .default("gel", self.gel)
            .default("fovy", self.fovy())
            .template(include_str!("phong_sensor.xml"))
    }
}

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
}

/// A camera-based tactile sensor: `read()` gives its colour image (the Phong optical model over
/// the depth its internal camera sees, on [`default_background`]), `read_depth()` that depth,
/// `contact()` what it feels. Frames are made at the sensor's rate on the platform's ticks:
/// after a tick that was due a frame, `read()` returns that frame. [`Digit`](super::Digit) and
/// [`GelSight2014`](super::GelSight2014) deref to one.
#[derive(Clone)]
pub struct PhongSensor {
    inner: Rc<Inner>,
}

struct Inner {
    spec: Spec,
    camera: Option<Camera>,
    clock: Clock,
    period: f64,
    state: RefCell<State>,
}

struct State {
    model: PhongModel,
    background: Vec<u8>,
    frame: RgbImage,
    depth: DepthImage,
    /// The depth the model sees: nothing beyond the gel's face, which is all the camera sees
    /// of what lies farther.
    gel: Vec<f32>,
    /// Platform time the next frame is due.
    due: f64,
    failed: Option<String>,
}

impl std::fmt::Debug for PhongSensor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PhongSensor")
            .field("sensor", &self.inner.spec.tag)
            .field("period", &self.inner.period)
            .finish()
    }
}

impl PhongSensor {
    /// The latest frame, RGB.
    pub fn read(&self) -> RgbImage {
        self.inner.state.borrow().frame.clone()
    }

    /// The depth the internal camera saw for the latest frame (metres from the camera, whose
    /// distance to the gel's outer face is the sensor's `gel_face`).
    pub fn read_depth(&self) -> DepthImage {
        self.inner.state.borrow().depth.clone()
    }

    /// What the latest frame feels.
    pub fn contact(&self) -> Contact {
        let state = self.inner.state.borrow();
        let spec = &self.inner.spec;
        let px2m = spec.params().px2m_ratio;
        let (mut deepest, mut touched) = (0.0f64, 0usize);
        for depth in state.depth.as_raw() {
            let indentation = (spec.gel_face - f64::from(*depth)).clamp(0.0, spec.thickness);
            deepest = deepest.max(indentation);
            touched += usize::from(indentation > TOUCHED);
        }
        Contact {
            in_contact: touched > 0,
            max_indentation: deepest,
            area: touched as f64 * px2m * px2m,
        }
    }
}

impl Inner {
    /// Makes a frame if one is due at platform time `now` (or `force`d).
    fn frame(&self, now: f64, force: bool) {
        let mut state = self.state.borrow_mut();
        if !force && now + 1e-9 < state.due {
            return;
        }
        state.due = now + self.period;
        let Some(camera) = &self.camera else {
            return;
        };
        match camera.depth() {
            Ok(depth) => {
                let State {
                    model,
                    background,
                    frame,
                    gel,
                    ..
                } = &mut *state;
                gel.clear();
                let face = self.spec.gel_face as f32;
                gel.extend(depth.as_raw().iter().map(|d| d.min(face)));
                if let Err(error) =
                    model.render_into(gel, self.spec.width as usize, background, frame)
                {
                    state.failed = Some(error.to_string());
                }
                state.depth = depth;
            }
            Err(error) => state.failed = Some(error.to_string()),
        }
    }
}

impl PhongSensor {
    /// Binds a sensor of `spec` whose internal camera is `camera` (none in `mock`).
    pub(super) fn bind<E: Environment>(
        spec: Spec,
        bind: &mut Bind<E>,
        camera: Option<Camera>,
    ) -> Result<Self, BindError> {
        let fps: f64 = bind.config_value("fps")?;
        if !(fps > 0.0 && fps.is_finite()) {
            return Err(bind.error(format!("fps must be a positive number, not {fps}")));
        }
        let noise: bool = bind.config_value("noise")?;
        let base = spec.params();
        let params = PhongParams {
            seed: bind.seed(),
            texture_sigma: if noise { base.texture_sigma } else { 0.0 },
            ..base
        };
        let (width, height) = (spec.width, spec.height);
        let background = default_background(width as usize, height as usize);
        let inner = Rc::new(Inner {
            spec,
            camera,
            clock: bind.clock(),
            period: 1.0 / fps,
            state: RefCell::new(State {
                model: PhongModel::new(params),
                frame: RgbImage::from_raw(width, height, background.clone())
                    .ok_or_else(|| bind.error("background size"))?,
                background,
                depth: DepthImage::from_pixel(width, height, image::Luma([f32::INFINITY])),
                gel: Vec::with_capacity((width * height) as usize),
                due: 0.0,
                failed: None,
            }),
        });
        inner.frame(inner.clock.time(), true);
        if let Some(error) = inner.state.borrow_mut().failed.take() {
            return Err(bind.error(error));
        }
        let ticking = Rc::clone(&inner);
        bind.on_tick(move || {
            // After a step the clock still reads the time before it.
            ticking.frame(ticking.clock.time() + ticking.clock.timestep(), false);
            match ticking.state.borrow_mut().failed.take() {
                Some(error) => Err(error.into()),
                None => Ok(()),
            }
        });
        Ok(Self { inner })
    }

    /// Binds a sensor of `spec` in `sim`: its internal camera renders depth with the fast
    /// preset, without the sensor's own geoms (group 3).
    pub(super) fn bind_sim(spec: Spec, bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let camera = bind
            .camera_with("camera", spec.width, spec.height, RenderPreset::Fast)?
            .hiding_groups(&[3]);
        Self::bind(spec, bind, Some(camera))
    }
}

/// A component newtype over [`PhongSensor`] for one [`Spec`]: `sim` and `mock` interfaces.
macro_rules! phong_sensor_component {
    ($(#[$doc:meta])* $name:ident, $spec:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone)]
        pub struct $name(PhongSensor);

        impl std::ops::Deref for $name {
            type Target = PhongSensor;

            fn deref(&self) -> &PhongSensor {
                &self.0
            }
        }

        impl yarok_core::component::Component for $name {
            fn declaration() -> yarok_core::component::Declaration {
                $spec.declaration()
            }

            fn interfaces(interfaces: &mut yarok_core::component::Interfaces<Self>) {
                interfaces.add::<yarok_mjc::Sim>().add::<yarok_core::component::Mock>();
            }
        }

        impl yarok_core::component::Interface<yarok_mjc::Sim> for $name {
            async fn bind(
                bind: &mut yarok_core::component::Bind<yarok_mjc::Sim>,
            ) -> Result<Self, yarok_core::component::BindError> {
                PhongSensor::bind_sim($spec, bind).map($name)
            }
        }

        impl yarok_core::component::Interface<yarok_core::component::Mock> for $name {
            async fn bind(
                bind: &mut yarok_core::component::Bind<yarok_core::component::Mock>,
            ) -> Result<Self, yarok_core::component::BindError> {
                PhongSensor::bind($spec, bind, None).map($name)
            }
        }
    };
}

pub(super) use phong_sensor_component;
