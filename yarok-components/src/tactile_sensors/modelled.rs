//! [`Modelled`]: a tactile sensor's frames made by its optical model from the depth of what
//! presses into its gel, at the sensor's frame rate on the platform's ticks — whatever senses
//! that depth ([`GelSensing`]: the simulation, or nothing in `mock`).

use std::cell::RefCell;
use std::rc::Rc;

use image::RgbImage;
use yarok_core::component::{Bind, BindError, Environment};
use yarok_core::time::Clock;
use yarok_mjc::DepthImage;

use super::kind::{Optics, SensorConfig, SensorKind};
use super::sensor::{Contact, GelContact, TactileError, TactileFeed, TactileSensor};
use crate::tactile::default_background;
use crate::tactile::elastomer::Elastomer;

/// Indentation (metres) above which a pixel counts as touched.
const TOUCHED: f64 = 2e-5;

/// What a sensor senses its gel with in one environment: its internal camera and MuJoCo's
/// contacts in `sim`, nothing in `mock`.
pub(super) trait GelSensing {
    /// Draws into `depth` what the internal camera sees of the world after the latest step
    /// (metres along its axis); leaves it as it is where nothing is seen.
    ///
    /// # Errors
    ///
    /// Why it could not be drawn.
    fn see(&self, depth: &mut DepthImage) -> Result<(), String>;

    /// The contacts on the gel after the latest step, in the sensor's frame.
    fn touches(&self) -> Vec<Touch>;
}

/// A contact on the gel, in the sensor's frame (its camera at the origin, looking along +z).
#[derive(Debug, Clone, Copy)]
pub(super) struct Touch {
    /// Where (metres).
    pub(super) position: [f64; 3],
    /// The unit direction it pushes the gel in (from what touches into the gel).
    pub(super) push: [f64; 3],
    /// The normal force (newtons).
    pub(super) normal_force: f64,
}

/// A sensor's frames made by its optical model from what it senses.
pub(super) struct Modelled {
    sensing: Box<dyn GelSensing>,
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

impl TactileFeed for Modelled {
    fn read(&self) -> RgbImage {
        self.state.borrow().frame.clone()
    }

    fn frame_time(&self) -> f64 {
        self.state.borrow().time
    }

    fn surface_distance(&self, x: f64, y: f64) -> Option<f64> {
        self.state.borrow().optics.surface_distance(x, y)
    }

    fn read_depth(&self) -> Result<DepthImage, TactileError> {
        Ok(self.state.borrow().depth.clone())
    }

    fn contact(&self) -> Result<Contact, TactileError> {
        let state = self.state.borrow();
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

    fn gel_contacts(&self) -> Result<Vec<GelContact>, TactileError> {
        Ok(self
            .sensing
            .touches()
            .into_iter()
            .map(|touch| GelContact {
                position: touch.position,
                normal_force: touch.normal_force,
            })
            .collect())
    }
}

impl Modelled {
    /// Binds a sensor of `kind` that senses with `sensing`: its first frame now, and one
    /// on each tick a frame is due.
    pub(super) fn bind<E: Environment>(
        kind: &dyn SensorKind,
        bind: &mut Bind<E>,
        sensing: Box<dyn GelSensing>,
    ) -> Result<TactileSensor, BindError> {
        let config: SensorConfig = bind.config()?;
        let fps = config.frame_rate(bind)?;
        let (noise, parallel) = (config.noise(), config.parallel());
        let calibration = config.calibration(kind, bind)?;
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
        let inner = Rc::new(Modelled {
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
        let sensor = TactileSensor::with_feed(bind, Rc::clone(&inner) as Rc<dyn TactileFeed>);
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

    /// The normal force on the gel (newtons) and the direction it pushes the gel in (a unit
    /// vector in the sensor's frame; the force-weighted mean of the contacts' normals).
    fn push(&self) -> (f64, [f64; 3]) {
        let (mut force, mut sum) = (0.0, [0.0; 3]);
        for touch in self.sensing.touches() {
            let pushing = touch.normal_force.max(0.0);
            force += pushing;
            for (sum, push) in sum.iter_mut().zip(touch.push) {
                *sum += pushing * push;
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
        if let Err(error) = self.sensing.see(&mut state.depth) {
            state.failed = Some(error);
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
