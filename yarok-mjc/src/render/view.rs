//! [`View`]: a model's scene drawn live into a [`Window`], seen from a free camera the mouse
//! moves or from one of the model's cameras, with text overlays.

use std::marker::PhantomData;
use std::sync::Arc;

use super::mujoco_scene::{ContextSpec, make_scene, update_scene};
use super::window::Window;
use super::{RenderError, RenderPreset};
use crate::{Data, Model, sys};

/// What a [`View`] can show beside the geoms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Visual {
    /// Contact points.
    Contacts,
    /// Contact forces.
    Forces,
    /// Every body's frame.
    Frames,
    /// Every camera (a tactile sensor's among them), with its frame.
    Cameras,
}

/// A corner of the view, for [`View::draw`]'s overlays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corner {
    /// The top left.
    TopLeft,
    /// The top right.
    TopRight,
    /// The bottom left.
    BottomLeft,
}

/// Two columns of text (lines separated by `\n`) in a corner of the view.
#[derive(Debug, Clone, Copy)]
pub struct Overlay<'a> {
    /// Where.
    pub corner: Corner,
    /// The left column.
    pub left: &'a str,
    /// The right column.
    pub right: &'a str,
}

/// A model's scene drawn into a window: the free camera (orbit, pan, zoom) or one of the
/// model's cameras; contacts, forces and frames on request. Not `Send`: the window's OpenGL
/// context belongs to its thread.
pub struct View {
    window: Window,
    model: Arc<Model>,
    scene: Box<sys::mjvScene>,
    context: Box<sys::mjrContext>,
    option: sys::mjvOption,
    perturb: sys::mjvPerturb,
    camera: sys::mjvCamera,
    /// The free camera, kept while a model camera is shown.
    free: sys::mjvCamera,
    _thread_bound: PhantomData<*const ()>,
}

impl std::fmt::Debug for View {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("View")
            .field("window", &self.window)
            .field("camera", &self.camera_name())
            .finish()
    }
}

impl View {
    /// Opens a window titled `title` of `width`×`height` pixels showing `model` from the free
    /// camera; `preset` as for offscreen renderers (multisampling is never used: the window
    /// has none), or, when `None`, [`RenderPreset::Fast`] under software OpenGL and
    /// [`RenderPreset::Quality`] on a GPU.
    ///
    /// # Errors
    ///
    /// [`RenderError::NoDisplay`] without an X server; [`RenderError::Egl`].
    pub fn open(
        model: &Arc<Model>,
        title: &str,
        (width, height): (u32, u32),
        preset: Option<RenderPreset>,
    ) -> Result<Self, RenderError> {
        let window = Window::open(title, width, height)?;
        let preset = preset.unwrap_or(if window.is_software() {
            RenderPreset::Fast
        } else {
            RenderPreset::Quality
        });
        let (scene, option, perturb) = make_scene(model, 10_000, preset == RenderPreset::Quality);
        // A small offscreen buffer: the view draws into the window's.
        let spec = ContextSpec {
            offscreen: (64, 64),
            multisampling: false,
            textures: true,
            font_scale: sys::mjFONTSCALE_150,
            buffer: sys::mjFB_WINDOW,
        };
        // SAFETY: the window's GL context is current on this thread; 64×64 is within any
        // implementation's limits.
        let context = unsafe { spec.make(model) };
        let mut free = sys::mjvCamera::default();
        // SAFETY: the model is valid and the camera owned.
        unsafe { model.mj().mjv_defaultFreeCamera(model.raw(), &mut free) };
        Ok(Self {
            window,
            model: Arc::clone(model),
            scene,
            context,
            option,
            perturb,
            camera: free,
            free,
            _thread_bound: PhantomData,
        })
    }

    /// The window's events since the last call.
    pub fn events(&mut self) -> Vec<super::WindowEvent> {
        self.window.events()
    }

    /// Width and height of the window in pixels.
    pub fn size(&self) -> (u32, u32) {
        self.window.size()
    }

    /// The window.
    pub fn window(&self) -> &Window {
        &self.window
    }

    /// Draws `data`'s state with `overlays` and shows it.
    ///
    /// # Errors
    ///
    /// [`RenderError::ModelMismatch`] for another model's data; [`RenderError::Egl`].
    pub fn draw(&mut self, data: &mut Data, overlays: &[Overlay<'_>]) -> Result<(), RenderError> {
        if data.model().signature() != self.model.signature() {
            return Err(RenderError::ModelMismatch);
        }
        self.window.make_current()?;
        let (width, height) = self.window.size();
        let viewport = sys::mjrRect {
            left: 0,
            bottom: 0,
            width: i32::try_from(width).unwrap_or(i32::MAX),
            height: i32::try_from(height).unwrap_or(i32::MAX),
        };
        let texts: Vec<_> = overlays
            .iter()
            .map(|o| (grid(o.corner), c_text(o.left), c_text(o.right)))
            .collect();
        let mj = self.model.mj();
        // SAFETY: the window's context is current; model, data, option, perturbation, camera
        // and scene belong to the same model (checked above); the texts are NUL-terminated and
        // outlive the calls.
        unsafe {
            update_scene(
                &self.model,
                data,
                &self.option,
                &self.perturb,
                &mut self.camera,
                &mut self.scene,
            );
            mj.mjr_setBuffer(sys::mjFB_WINDOW as i32, &mut *self.context);
            mj.mjr_render(viewport, &mut *self.scene, &*self.context);
            for (grid, left, right) in &texts {
                mj.mjr_overlay(
                    sys::mjFONT_NORMAL as i32,
                    *grid,
                    viewport,
                    left.as_ptr(),
                    right.as_ptr(),
                    &*self.context,
                );
            }
        }
        self.window.swap()
    }

    /// Turns the free camera round its look-at point by a drag of `(dx, dy)` pixels.
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        self.move_camera(sys::mjMOUSE_ROTATE_V, dx, dy);
    }

    /// Moves the free camera sideways and up by a drag of `(dx, dy)` pixels.
    pub fn pan(&mut self, dx: f64, dy: f64) {
        self.move_camera(sys::mjMOUSE_MOVE_V, dx, dy);
    }

    /// Moves the free camera towards its look-at point (positive `steps`) or away.
    pub fn zoom(&mut self, steps: f64) {
        let (_, height) = self.window.size();
        self.move_camera(sys::mjMOUSE_ZOOM, 0.0, -0.05 * steps * f64::from(height));
    }

    fn move_camera(&mut self, action: sys::mjtMouse_, dx: f64, dy: f64) {
        if self.camera.type_ != sys::mjCAMERA_FREE as i32 {
            return;
        }
        let height = f64::from(self.window.size().1);
        // SAFETY: the model and the camera are valid; the camera is a free one.
        unsafe {
            self.model.mj().mjv_moveCamera(
                self.model.raw(),
                action as i32,
                dx / height,
                dy / height,
                &mut self.camera,
            );
        }
        self.free = self.camera;
    }

    /// Shows the next of the model's cameras, or the free camera after the last.
    pub fn next_camera(&mut self) {
        let cameras = self.model.count(crate::ObjectKind::Camera);
        let next = if self.camera.type_ == sys::mjCAMERA_FIXED as i32 {
            usize::try_from(self.camera.fixedcamid).map_or(0, |id| id + 1)
        } else {
            0
        };
        self.camera = if next < cameras {
            sys::mjvCamera {
                type_: sys::mjCAMERA_FIXED as i32,
                fixedcamid: i32::try_from(next).unwrap_or(-1),
                ..Default::default()
            }
        } else {
            self.free
        };
    }

    /// The camera shown: `free`, or the model camera's name.
    pub fn camera_name(&self) -> String {
        if self.camera.type_ != sys::mjCAMERA_FIXED as i32 {
            return "free".into();
        }
        let index = usize::try_from(self.camera.fixedcamid).unwrap_or(0);
        self.model
            .name_of(crate::ObjectKind::Camera, index)
            .unwrap_or_else(|| format!("camera {index}"))
    }

    /// Shows `visual` if hidden, hides it if shown; whether it is shown now.
    pub fn toggle(&mut self, visual: Visual) -> bool {
        let flag = match visual {
            Visual::Contacts => &mut self.option.flags[sys::mjVIS_CONTACTPOINT as usize],
            Visual::Forces => &mut self.option.flags[sys::mjVIS_CONTACTFORCE as usize],
            Visual::Frames => return self.toggle_frames(sys::mjFRAME_BODY),
            Visual::Cameras => {
                let shown = self.toggle_frames(sys::mjFRAME_CAMERA);
                self.option.flags[sys::mjVIS_CAMERA as usize] = u8::from(shown);
                return shown;
            }
        };
        *flag = u8::from(*flag == 0);
        *flag != 0
    }

    /// Shows the frames of `kind` (bodies', cameras') instead of any other, or hides them if
    /// shown; whether they are shown now.
    fn toggle_frames(&mut self, kind: sys::mjtFrame_) -> bool {
        let shown = self.option.frame == kind as i32;
        self.option.frame = if shown { sys::mjFRAME_NONE } else { kind } as i32;
        !shown
    }
}

fn grid(corner: Corner) -> i32 {
    (match corner {
        Corner::TopLeft => sys::mjGRID_TOPLEFT,
        Corner::TopRight => sys::mjGRID_TOPRIGHT,
        Corner::BottomLeft => sys::mjGRID_BOTTOMLEFT,
    }) as i32
}

fn c_text(text: &str) -> std::ffi::CString {
    std::ffi::CString::new(text.replace('\0', " ")).unwrap_or_default()
}

impl Drop for View {
    fn drop(&mut self) {
        let mj = self.model.mj();
        if self.window.make_current().is_ok() {
            // SAFETY: the context that owns these GL resources is current; freed once.
            unsafe { mj.mjr_freeContext(&mut *self.context) };
        }
        // SAFETY: the scene was made by mjv_makeScene and is freed once.
        unsafe { mj.mjv_freeScene(&mut *self.scene) };
    }
}
