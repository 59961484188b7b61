//! [`Gallery`]: a window showing images side by side, each under its label.

use std::marker::PhantomData;
use std::sync::Arc;

use super::RenderError;
use super::mujoco_scene::ContextSpec;
use super::window::{Window, WindowEvent};
use crate::{Model, sys};

/// Pixels between images, and above each for its label.
const GAP: u32 = 4;
const LABEL: u32 = 24;

/// An RGB image (`3 · width · height` bytes, top row first) and its label.
#[derive(Debug, Clone, Copy)]
pub struct Picture<'a> {
    /// What it shows (`/arm/gripper/left_digit image`).
    pub label: &'a str,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// The pixels, RGB interleaved, top row first.
    pub rgb: &'a [u8],
}

/// A window showing pictures side by side in rows, at their own size, each under its label;
/// the window grows to fit them. Not `Send`.
pub struct Gallery {
    window: Window,
    /// MuJoCo's rendering context, for its pixel and text drawing (made from an empty model).
    model: Arc<Model>,
    context: Box<sys::mjrContext>,
    /// Bottom-up rows of the picture being drawn.
    flipped: Vec<u8>,
    _thread_bound: PhantomData<*const ()>,
}

impl std::fmt::Debug for Gallery {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Gallery")
            .field("window", &self.window)
            .finish()
    }
}

impl Gallery {
    /// Opens an empty gallery window titled `title`.
    ///
    /// # Errors
    ///
    /// [`RenderError::NoDisplay`] without an X server; [`RenderError::Egl`]; a
    /// [`RenderError::Library`] without libmujoco.
    pub fn open(title: &str) -> Result<Self, RenderError> {
        let window = Window::open(title, 320, 240)?;
        let model = Arc::new(Model::from_xml_str("<mujoco/>")?);
        let spec = ContextSpec {
            offscreen: (16, 16),
            multisampling: false,
            textures: false,
            font_scale: sys::mjFONTSCALE_100,
            buffer: sys::mjFB_WINDOW,
        };
        // SAFETY: the window's GL context is current on this thread; 16×16 is within any
        // implementation's limits.
        let context = unsafe { spec.make(&model) };
        Ok(Self {
            window,
            model,
            context,
            flipped: Vec::new(),
            _thread_bound: PhantomData,
        })
    }

    /// The window's events since the last call.
    pub fn events(&mut self) -> Vec<WindowEvent> {
        self.window.events()
    }

    /// The window.
    pub fn window(&self) -> &Window {
        &self.window
    }

    /// Shows `pictures`, in rows no wider than `max_width` pixels.
    ///
    /// # Errors
    ///
    /// [`RenderError::Empty`] for a picture whose pixels do not fill its size;
    /// [`RenderError::Egl`].
    pub fn show(&mut self, pictures: &[Picture<'_>], max_width: u32) -> Result<(), RenderError> {
        let places = layout(pictures, max_width);
        let width = places.iter().map(|p| p.0 + p.2).max().unwrap_or(1) + GAP;
        let height = places.iter().map(|p| p.1 + p.3).max().unwrap_or(1) + GAP;
        if self.window.size() != (width, height) {
            self.window.resize(width, height);
        }
        self.window.make_current()?;
        let mj = self.model.mj();
        let whole = rect(0, 0, width, height);
        // SAFETY: the window's context is current and the rectangle within the window.
        unsafe {
            mj.mjr_setBuffer(sys::mjFB_WINDOW as i32, &mut *self.context);
            mj.mjr_rectangle(whole, 0.1, 0.1, 0.12, 1.0);
        }
        for (picture, (x, y, w, h)) in pictures.iter().zip(places) {
            if picture.rgb.len() != 3 * w as usize * h as usize {
                return Err(RenderError::Empty {
                    width: picture.width,
                    height: picture.height,
                });
            }
            // OpenGL draws rows bottom-up; the window's origin is its bottom left.
            self.flipped.clear();
            let row = 3 * w as usize;
            self.flipped
                .extend(picture.rgb.chunks_exact(row).rev().flatten());
            let bottom = height - y - h;
            let label =
                std::ffi::CString::new(picture.label.replace('\0', " ")).unwrap_or_default();
            // SAFETY: the context is current; the pixels fill the viewport (checked above);
            // the label is NUL-terminated.
            unsafe {
                mj.mjr_drawPixels(
                    self.flipped.as_ptr(),
                    std::ptr::null(),
                    rect(x, bottom, w, h),
                    &*self.context,
                );
                mj.mjr_text(
                    sys::mjFONT_NORMAL as i32,
                    label.as_ptr(),
                    &*self.context,
                    x as f32 / width as f32,
                    (bottom + h + 6) as f32 / height as f32,
                    0.9,
                    0.9,
                    0.9,
                );
            }
        }
        self.window.swap()
    }
}

fn rect(left: u32, bottom: u32, width: u32, height: u32) -> sys::mjrRect {
    let int = |v: u32| i32::try_from(v).unwrap_or(i32::MAX);
    sys::mjrRect {
        left: int(left),
        bottom: int(bottom),
        width: int(width),
        height: int(height),
    }
}

/// Each picture's place — left, top (from the window's top), width, height — in rows no wider
/// than `max_width`.
fn layout(pictures: &[Picture<'_>], max_width: u32) -> Vec<(u32, u32, u32, u32)> {
    let (mut x, mut y, mut row_height) = (GAP, 0, 0);
    pictures
        .iter()
        .map(|p| {
            if x > GAP && x + p.width + GAP > max_width {
                (x, y, row_height) = (GAP, y + row_height, 0);
            }
            let place = (x, y + LABEL, p.width, p.height);
            x += p.width + GAP;
            row_height = row_height.max(LABEL + p.height + GAP);
            place
        })
        .collect()
}

impl Drop for Gallery {
    fn drop(&mut self) {
        if self.window.make_current().is_ok() {
            // SAFETY: the context that owns these GL resources is current; freed once.
            unsafe { self.model.mj().mjr_freeContext(&mut *self.context) };
        }
    }
}
