//! [`Gallery`]: a window showing images side by side, each under its label, and a table of
//! text rows under them.

use std::marker::PhantomData;
use std::sync::Arc;

use super::RenderError;
use super::mujoco_scene::ContextSpec;
use super::window::{Window, WindowEvent};
use crate::{Model, sys};

/// Pixels between images, and above each for its label.
const GAP: u32 = 4;
const LABEL: u32 = 24;
/// Pixels between a table row's name and its value, and between rows.
const COLUMN_GAP: u32 = 16;
const ROW_GAP: u32 = 3;

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

/// A row of the table under the pictures: a name and its value, one line each.
#[derive(Debug, Clone, Copy)]
pub struct TextRow<'a> {
    /// What the value is (`/arm state q`).
    pub name: &'a str,
    /// The value (`0.000 -1.571 1.571`).
    pub value: &'a str,
}

/// A window showing pictures side by side in rows, at their own size, each under its label,
/// and a table of text rows under them; the window grows to fit them. Not `Send`.
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

    /// Shows `pictures`, in rows no wider than `max_width` pixels, and `table` under them.
    ///
    /// # Errors
    ///
    /// [`RenderError::Empty`] for a picture whose pixels do not fill its size;
    /// [`RenderError::Egl`].
    pub fn show(
        &mut self,
        pictures: &[Picture<'_>],
        table: &[TextRow<'_>],
        max_width: u32,
    ) -> Result<(), RenderError> {
        let places = layout(pictures, max_width);
        let pictures_bottom = places.iter().map(|p| p.1 + p.3).max().unwrap_or(0) + GAP;
        let line = u32::try_from(self.context.charHeight).unwrap_or(0) + ROW_GAP;
        let names_width = table.iter().map(|row| self.text_width(row.name)).max();
        let value_left = GAP + names_width.unwrap_or(0) + COLUMN_GAP;
        let values_width = table.iter().map(|row| self.text_width(row.value)).max();
        let width = (places.iter().map(|p| p.0 + p.2).max().unwrap_or(1) + GAP)
            .max(values_width.map_or(1, |w| value_left + w + GAP));
        let height = pictures_bottom + line * table.len() as u32;
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
            // SAFETY: the context is current; the pixels fill the viewport (checked above).
            unsafe {
                mj.mjr_drawPixels(
                    self.flipped.as_ptr(),
                    std::ptr::null(),
                    rect(x, bottom, w, h),
                    &*self.context,
                );
            }
            let label_at = [
                x as f32 / width as f32,
                (bottom + h + 6) as f32 / height as f32,
            ];
            self.text(picture.label, label_at, 0.9);
        }
        let table_height = height - pictures_bottom;
        // SAFETY: the context is current and the rectangle within the window; it also makes the
        // table's rectangle the viewport its text is placed in.
        unsafe { mj.mjr_rectangle(rect(0, 0, width, table_height), 0.13, 0.13, 0.15, 1.0) };
        for (index, row) in table.iter().enumerate() {
            let baseline = table_height - line * (index as u32 + 1) + line / 4;
            for (left, text, shade) in [(GAP, row.name, 0.7), (value_left, row.value, 0.95)] {
                let at = [
                    left as f32 / width as f32,
                    baseline as f32 / table_height as f32,
                ];
                self.text(text, at, shade);
            }
        }
        self.window.swap()
    }

    /// Draws `text` in the normal font, grey of `shade`, at `at` (left, baseline) in the current
    /// viewport's relative coordinates.
    fn text(&self, text: &str, at: [f32; 2], shade: f32) {
        let text = std::ffi::CString::new(text.replace('\0', " ")).unwrap_or_default();
        // SAFETY: the window's context is current (made so by `show`); the text is
        // NUL-terminated and outlives the call.
        unsafe {
            self.model.mj().mjr_text(
                sys::mjFONT_NORMAL as i32,
                text.as_ptr(),
                &*self.context,
                at[0],
                at[1],
                shade,
                shade,
                shade,
            );
        }
    }

    /// How wide `text` is drawn in the normal font (pixels); characters the font lacks count as
    /// a space.
    fn text_width(&self, text: &str) -> u32 {
        let widths = &self.context.charWidth;
        let width = |c: char| {
            let known = usize::try_from(u32::from(c))
                .ok()
                .filter(|&c| c < widths.len());
            widths[known.unwrap_or(usize::from(b' '))]
        };
        u32::try_from(text.chars().map(width).sum::<i32>()).unwrap_or(0)
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
