//! [`Digit`]: a DIGIT tactile sensor in the world, its image from the DIGIT optical model over
//! the depth its internal camera renders, at the sensor's frame rate.

use std::cell::RefCell;
use std::rc::Rc;

use image::RgbImage;
use yarok_core::component::{
    Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, Mock,
};
use yarok_core::time::Clock;
use yarok_mjc::{Camera, DepthImage, RenderPreset, Sim, SimBind};

use crate::tactile::default_background;
use crate::tactile::phong::{PhongModel, PhongParams};

/// Image size: 240 columns × 320 rows, as the DIGIT delivers QVGA frames (portrait).
const WIDTH: u32 = 240;
const HEIGHT: u32 = 320;

/// Distance from the camera to the gel's outer face, and the gel's thickness (metres).
const GEL_FACE: f64 = 0.018;
const GEL_THICKNESS: f64 = 0.002;

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

/// A DIGIT tactile sensor: `read()` gives its 240 × 320 colour image (the DIGIT optical model
/// over the depth its internal camera sees, on [`default_background`]), `read_depth()` that depth, `contact()` what it
/// feels. Frames are made at `fps` (default 60, the DIGIT's QVGA rate) on the platform's ticks:
/// after a tick that was due a frame, `read()` returns that frame.
///
/// Tag `digit`; config `pos` and `quat` (placement; it senses along its +z), `fps`, `noise`
/// (the gel's texture noise, default on, seeded from the platform's seed). Mount it on a
/// gripper pad with `parent=` and a `quat` that turns +z inward.
///
/// Environments: `sim`; `mock` (always the untouched background).
#[derive(Clone)]
pub struct Digit {
    inner: Rc<Inner>,
}

struct Inner {
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

impl std::fmt::Debug for Digit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Digit")
            .field("period", &self.inner.period)
            .finish()
    }
}

impl Digit {
    /// The latest frame: RGB, 240 columns × 320 rows.
    pub fn read(&self) -> RgbImage {
        self.inner.state.borrow().frame.clone()
    }

    /// The depth the internal camera saw for the latest frame (metres from the camera; the
    /// gel's outer face is at 0.018).
    pub fn read_depth(&self) -> DepthImage {
        self.inner.state.borrow().depth.clone()
    }

    /// What the latest frame feels.
    pub fn contact(&self) -> Contact {
        let state = self.inner.state.borrow();
        let px2m = params().px2m_ratio;
        let (mut deepest, mut touched) = (0.0f64, 0usize);
        for depth in state.depth.as_raw() {
            let indentation = (GEL_FACE - f64::from(*depth)).clamp(0.0, GEL_THICKNESS);
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
                gel.extend(depth.as_raw().iter().map(|d| d.min(GEL_FACE as f32)));
                if let Err(error) = model.render_into(gel, WIDTH as usize, background, frame) {
                    state.failed = Some(error.to_string());
                }
                state.depth = depth;
            }
            Err(error) => state.failed = Some(error.to_string()),
        }
    }
}

/// The DIGIT model's parameters for this sensor's geometry: the gel between 16 and 18 mm from
/// the camera.
fn params() -> PhongParams {
    PhongParams {
        elastomer_thickness: GEL_THICKNESS,
        min_depth: GEL_FACE - GEL_THICKNESS,
        ..PhongParams::digit_metric()
    }
}

impl Component for Digit {
    fn declaration() -> Declaration {
        Declaration::new("digit")
            .default("pos", [0.0; 3])
            .default("quat", [1.0, 0.0, 0.0, 0.0])
            .default("fps", 60.0)
            .default("noise", true)
            .template(include_str!("digit.xml"))
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>();
    }
}

impl Digit {
    fn bind_with<E: Environment>(
        bind: &mut Bind<E>,
        camera: Option<Camera>,
    ) -> Result<Self, BindError> {
        let fps: f64 = bind.config_value("fps")?;
        if !(fps > 0.0 && fps.is_finite()) {
            return Err(bind.error(format!("fps must be a positive number, not {fps}")));
        }
        let noise: bool = bind.config_value("noise")?;
        let params = PhongParams {
            seed: bind.seed(),
            texture_sigma: if noise { params().texture_sigma } else { 0.0 },
            ..params()
        };
        let background = default_background(WIDTH as usize, HEIGHT as usize);
        let inner = Rc::new(Inner {
            camera,
            clock: bind.clock(),
            period: 1.0 / fps,
            state: RefCell::new(State {
                model: PhongModel::new(params),
                frame: RgbImage::from_raw(WIDTH, HEIGHT, background.clone())
                    .ok_or_else(|| bind.error("background size"))?,
                background,
                depth: DepthImage::from_pixel(WIDTH, HEIGHT, image::Luma([f32::INFINITY])),
                gel: Vec::with_capacity((WIDTH * HEIGHT) as usize),
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
}

impl Interface<Sim> for Digit {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let camera = bind
            .camera_with("camera", WIDTH, HEIGHT, RenderPreset::Fast)?
            .hiding_groups(&[3]);
        Self::bind_with(bind, Some(camera))
    }
}

impl Interface<Mock> for Digit {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Self::bind_with(bind, None)
    }
}
