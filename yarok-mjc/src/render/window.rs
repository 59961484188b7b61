//! [`Window`]: an X11 window with an OpenGL context drawing into it through EGL, and the
//! input events it receives.

use std::ffi::{CString, c_void};
use std::os::raw::{c_int, c_uint, c_ulong};

use khronos_egl as egl;
use x11_dl::keysym;
use x11_dl::xlib::{self, Xlib};

use super::RenderError;
use super::egl::{Egl, egl_error, x11_display};

/// A key the viewer knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Key {
    /// A printable character (lower case for letters).
    Char(char),
    /// The space bar.
    Space,
    /// The right arrow.
    Right,
    /// The backspace key.
    Backspace,
    /// The tab key.
    Tab,
    /// The escape key.
    Escape,
    /// F1.
    F1,
}

/// A mouse button.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Button {
    /// The left button.
    Left,
    /// The middle button (or wheel press).
    Middle,
    /// The right button.
    Right,
}

/// What happened to a window.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum WindowEvent {
    /// A key was pressed.
    Key(Key),
    /// A button was pressed at pixel `(x, y)`.
    Press(Button, f64, f64),
    /// A button was released.
    Release(Button),
    /// The pointer moved to pixel `(x, y)`.
    Motion(f64, f64),
    /// The wheel turned: positive away from the user.
    Scroll(f64),
    /// The user asked to close the window.
    Close,
}

/// An X11 window whose OpenGL (compatibility) context is current on the thread that opened
/// it; not `Send`.
pub struct Window {
    xlib: Xlib,
    display: *mut xlib::Display,
    window: xlib::Window,
    delete_atom: xlib::Atom,
    egl: &'static Egl,
    egl_display: egl::Display,
    surface: egl::Surface,
    context: egl::Context,
    size: (u32, u32),
}

impl std::fmt::Debug for Window {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Window")
            .field("window", &self.window)
            .field("size", &self.size)
            .finish()
    }
}

const CONFIG: [egl::Int; 13] = [
    egl::SURFACE_TYPE,
    egl::WINDOW_BIT,
    egl::RENDERABLE_TYPE,
    egl::OPENGL_BIT,
    egl::RED_SIZE,
    8,
    egl::GREEN_SIZE,
    8,
    egl::BLUE_SIZE,
    8,
    egl::DEPTH_SIZE,
    24,
    egl::NONE,
];

impl Window {
    /// Opens a window titled `title` of `width`×`height` pixels on the X server `$DISPLAY`
    /// names, and makes its OpenGL context current.
    ///
    /// # Errors
    ///
    /// [`RenderError::NoDisplay`] without an X server; [`RenderError::Egl`] when it offers
    /// no OpenGL window.
    pub fn open(title: &str, width: u32, height: u32) -> Result<Self, RenderError> {
        let no_display = |reason: String| RenderError::NoDisplay {
            display: std::env::var("DISPLAY").unwrap_or_default(),
            reason,
        };
        let xlib = Xlib::open().map_err(|e| no_display(e.to_string()))?;
        // SAFETY: XOpenDisplay accepts null (the DISPLAY variable's server).
        let display = unsafe { (xlib.XOpenDisplay)(std::ptr::null()) };
        if display.is_null() {
            return Err(no_display("no X server answers".into()));
        }
        // SAFETY: `display` is open; the window is a child of its default root window, and
        // every string passed is NUL-terminated and outlives the call.
        let (window, delete_atom) = unsafe {
            let screen = (xlib.XDefaultScreen)(display);
            let root = (xlib.XRootWindow)(display, screen);
            let black = (xlib.XBlackPixel)(display, screen);
            let window =
                (xlib.XCreateSimpleWindow)(display, root, 0, 0, width, height, 0, black, black);
            let title = CString::new(title.replace('\0', " ")).unwrap_or_default();
            (xlib.XStoreName)(display, window, title.as_ptr());
            (xlib.XSelectInput)(
                display,
                window,
                xlib::KeyPressMask
                    | xlib::ButtonPressMask
                    | xlib::ButtonReleaseMask
                    | xlib::PointerMotionMask
                    | xlib::StructureNotifyMask,
            );
            let name = c"WM_DELETE_WINDOW";
            let mut delete_atom = (xlib.XInternAtom)(display, name.as_ptr(), xlib::False);
            (xlib.XSetWMProtocols)(display, window, &mut delete_atom, 1);
            (xlib.XMapWindow)(display, window);
            (xlib.XFlush)(display);
            (window, delete_atom)
        };
        // SAFETY: `display` is open and stays so until this window is dropped.
        let surface = unsafe { Self::surface(display, window) };
        let (egl, egl_display, surface, context) = match surface {
            Ok(parts) => parts,
            Err(error) => {
                // SAFETY: the window and display were opened above and are not used again.
                unsafe {
                    (xlib.XDestroyWindow)(display, window);
                    (xlib.XCloseDisplay)(display);
                }
                return Err(error);
            }
        };
        Ok(Self {
            xlib,
            display,
            window,
            delete_atom,
            egl,
            egl_display,
            surface,
            context,
            size: (width, height),
        })
    }

    /// An EGL window surface on `window` and a current OpenGL context for it.
    ///
    /// # Safety
    ///
    /// `display` is open and `window` one of its windows.
    unsafe fn surface(
        display: *mut xlib::Display,
        window: xlib::Window,
    ) -> Result<(&'static Egl, egl::Display, egl::Surface, egl::Context), RenderError> {
        // SAFETY: the caller's display is open and outlives the EGL display's use.
        let (egl, egl_display) = unsafe { x11_display(display.cast::<c_void>()) }?;
        let config = egl
            .choose_first_config(egl_display, &CONFIG)
            .map_err(|e| egl_error("choose a window config", e))?
            .ok_or_else(|| {
                egl_error("choose a window config", "no RGB8 + depth24 window config")
            })?;
        egl.bind_api(egl::OPENGL_API)
            .map_err(|e| egl_error("bind the OpenGL API", e))?;
        // SAFETY: `window` is a live X11 window of the display EGL was given.
        let surface = unsafe {
            egl.create_window_surface(egl_display, config, window as egl::NativeWindowType, None)
        }
        .map_err(|e| egl_error("create a window surface", e))?;
        let context = egl
            .create_context(egl_display, config, None, &[egl::NONE])
            .map_err(|e| egl_error("create an OpenGL context", e))?;
        egl.make_current(egl_display, Some(surface), Some(surface), Some(context))
            .map_err(|e| egl_error("make the window's context current", e))?;
        // Frames are paced by the viewer, not by the screen's refresh.
        let _no_vsync = egl.swap_interval(egl_display, 0);
        Ok((egl, egl_display, surface, context))
    }

    /// Makes this window's context current (the thread's offscreen renderers make theirs
    /// current when they draw).
    ///
    /// # Errors
    ///
    /// [`RenderError::Egl`].
    pub fn make_current(&self) -> Result<(), RenderError> {
        if self.egl.get_current_context() == Some(self.context) {
            return Ok(());
        }
        self.egl
            .make_current(
                self.egl_display,
                Some(self.surface),
                Some(self.surface),
                Some(self.context),
            )
            .map_err(|e| egl_error("make the window's context current", e))
    }

    /// Shows what was drawn.
    ///
    /// # Errors
    ///
    /// [`RenderError::Egl`].
    pub fn swap(&self) -> Result<(), RenderError> {
        self.egl
            .swap_buffers(self.egl_display, self.surface)
            .map_err(|e| egl_error("swap the window's buffers", e))
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// Sets the title.
    pub fn set_title(&self, title: &str) {
        let title = CString::new(title.replace('\0', " ")).unwrap_or_default();
        // SAFETY: the display and window are open; the title is NUL-terminated.
        unsafe {
            (self.xlib.XStoreName)(self.display, self.window, title.as_ptr());
            (self.xlib.XFlush)(self.display);
        }
    }

    /// Resizes the window.
    pub fn resize(&mut self, width: u32, height: u32) {
        // SAFETY: the display and window are open.
        unsafe {
            (self.xlib.XResizeWindow)(self.display, self.window, width.max(1), height.max(1));
            (self.xlib.XFlush)(self.display);
        }
        self.size = (width.max(1), height.max(1));
    }

    /// Whether OpenGL is drawn by the CPU (Mesa's llvmpipe or softpipe), where shadows,
    /// reflections and multisampling cost several times the frame.
    pub fn is_software(&self) -> bool {
        type GetString = unsafe extern "system" fn(u32) -> *const std::os::raw::c_char;
        const GL_RENDERER: u32 = 0x1F01;
        let Some(get) = self.egl.get_proc_address("glGetString") else {
            return false;
        };
        if self.make_current().is_err() {
            return false;
        }
        // SAFETY: glGetString has the GetString signature (OpenGL 1.0); the window's context
        // is current; it returns a static NUL-terminated string, or null.
        let name = unsafe {
            let get = std::mem::transmute::<extern "system" fn(), GetString>(get);
            let name = get(GL_RENDERER);
            if name.is_null() {
                return false;
            }
            std::ffi::CStr::from_ptr(name)
                .to_string_lossy()
                .to_lowercase()
        };
        name.contains("llvmpipe") || name.contains("softpipe") || name.contains("software")
    }

    /// The events since the last call, without waiting.
    pub fn events(&mut self) -> Vec<WindowEvent> {
        let mut events = Vec::new();
        // SAFETY: the display is open; XNextEvent fills the event it is given, and only the
        // union member its type names is read.
        unsafe {
            while (self.xlib.XPending)(self.display) > 0 {
                let mut event: xlib::XEvent = std::mem::zeroed();
                (self.xlib.XNextEvent)(self.display, &mut event);
                match event.get_type() {
                    xlib::KeyPress => {
                        let symbol = (self.xlib.XLookupKeysym)(&mut event.key, 0);
                        events.extend(key(symbol).map(WindowEvent::Key));
                    }
                    xlib::ButtonPress => {
                        let (x, y) = (f64::from(event.button.x), f64::from(event.button.y));
                        events.extend(match event.button.button {
                            4 => Some(WindowEvent::Scroll(1.0)),
                            5 => Some(WindowEvent::Scroll(-1.0)),
                            other => button(other).map(|b| WindowEvent::Press(b, x, y)),
                        });
                    }
                    xlib::ButtonRelease => {
                        events.extend(button(event.button.button).map(WindowEvent::Release));
                    }
                    xlib::MotionNotify => {
                        let (x, y) = (f64::from(event.motion.x), f64::from(event.motion.y));
                        events.push(WindowEvent::Motion(x, y));
                    }
                    xlib::ConfigureNotify => {
                        let (width, height) = (event.configure.width, event.configure.height);
                        self.size = (to_u32(width), to_u32(height));
                    }
                    xlib::ClientMessage
                        if event.client_message.data.get_long(0) as c_ulong == self.delete_atom =>
                    {
                        events.push(WindowEvent::Close);
                    }
                    xlib::DestroyNotify => events.push(WindowEvent::Close),
                    _ => {}
                }
            }
        }
        events
    }
}

fn to_u32(value: c_int) -> u32 {
    u32::try_from(value).unwrap_or(0).max(1)
}

fn button(button: c_uint) -> Option<Button> {
    match button {
        1 => Some(Button::Left),
        2 => Some(Button::Middle),
        3 => Some(Button::Right),
        _ => None,
    }
}

fn key(symbol: xlib::KeySym) -> Option<Key> {
    let symbol = u32::try_from(symbol).ok()?;
    Some(match symbol {
        keysym::XK_space => Key::Space,
        keysym::XK_Right => Key::Right,
        keysym::XK_BackSpace => Key::Backspace,
        keysym::XK_Tab => Key::Tab,
        keysym::XK_Escape => Key::Escape,
        keysym::XK_F1 => Key::F1,
        keysym::XK_KP_Add => Key::Char('+'),
        keysym::XK_KP_Subtract => Key::Char('-'),
        printable @ 0x21..=0x7E => Key::Char(char::from_u32(printable)?.to_ascii_lowercase()),
        _ => return None,
    })
}

impl Drop for Window {
    fn drop(&mut self) {
        if self.egl.get_current_context() == Some(self.context) {
            let _released = self.egl.make_current(self.egl_display, None, None, None);
        }
        let _destroyed = self.egl.destroy_context(self.egl_display, self.context);
        let _destroyed = self.egl.destroy_surface(self.egl_display, self.surface);
        let _terminated = self.egl.terminate(self.egl_display);
        // SAFETY: the window and display were opened by `open` and are not used after this.
        unsafe {
            (self.xlib.XDestroyWindow)(self.display, self.window);
            (self.xlib.XCloseDisplay)(self.display);
        }
    }
}
