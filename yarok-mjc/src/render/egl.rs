//! A headless OpenGL context through EGL: the device platform first, Mesa's surfaceless
//! platform as the fallback. Works with Mesa's llvmpipe on machines without a GPU, where
//! threads' contexts are spread over the displays EGL offers: llvmpipe rasterizes the
//! contexts of one display one at a time.

use std::cell::RefCell;
use std::ffi::{CStr, c_char, c_void};
use std::rc::{Rc, Weak};
use std::sync::{Mutex, OnceLock};

use khronos_egl as egl;
use libloading::os::unix::{Library, RTLD_GLOBAL, RTLD_NOW};

use super::RenderError;

pub(super) type Egl = egl::DynamicInstance<egl::EGL1_4>;

const PLATFORM_DEVICE: egl::Enum = 0x313F;
const PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;
const MAX_DEVICES: usize = 16;
/// `EGL_EXTENSIONS`, as `eglQueryDeviceStringEXT` takes it.
const EXTENSIONS: egl::Int = 0x3055;

/// How many live contexts each display (by its handle's address) has.
static DISPLAY_USERS: Mutex<Vec<(usize, usize)>> = Mutex::new(Vec::new());

fn display_users(display: usize) -> usize {
    let users = DISPLAY_USERS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    users
        .iter()
        .find(|(known, _)| *known == display)
        .map_or(0, |(_, count)| *count)
}

/// Adds `change` (+1 or −1) to `display`'s live contexts.
fn count_user(display: usize, change: isize) {
    let mut users = DISPLAY_USERS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    match users.iter_mut().find(|(known, _)| *known == display) {
        Some((_, count)) => *count = count.saturating_add_signed(change),
        None => users.push((display, change.max(0).unsigned_abs())),
    }
}

type QueryDevices =
    unsafe extern "system" fn(egl::Int, *mut *mut c_void, *mut egl::Int) -> egl::Boolean;
type QueryDeviceString = unsafe extern "system" fn(*mut c_void, egl::Int) -> *const c_char;
type GetPlatformDisplay =
    unsafe extern "system" fn(egl::Enum, *mut c_void, *const egl::Int) -> egl::EGLDisplay;
type GetIntegerv = unsafe extern "system" fn(u32, *mut i32);
type GenObjects = unsafe extern "system" fn(i32, *mut u32);
type DeleteObjects = unsafe extern "system" fn(i32, *const u32);
type BindObject = unsafe extern "system" fn(u32, u32);
type RenderbufferStorageMultisample = unsafe extern "system" fn(u32, i32, u32, i32, i32);
type FramebufferRenderbuffer = unsafe extern "system" fn(u32, u32, u32, u32);
type CheckFramebufferStatus = unsafe extern "system" fn(u32) -> u32;

/// The OpenGL 3.0 functions that query limits and make and check a framebuffer.
struct GlFunctions {
    get_integer: GetIntegerv,
    gen_framebuffers: GenObjects,
    delete_framebuffers: DeleteObjects,
    bind_framebuffer: BindObject,
    gen_renderbuffers: GenObjects,
    delete_renderbuffers: DeleteObjects,
    bind_renderbuffer: BindObject,
    renderbuffer_storage: RenderbufferStorageMultisample,
    framebuffer_renderbuffer: FramebufferRenderbuffer,
    check_framebuffer_status: CheckFramebufferStatus,
}

impl GlFunctions {
    fn load(egl: &Egl) -> Result<Self, RenderError> {
        let find = |name: &'static str| {
            egl.get_proc_address(name)
                .ok_or_else(|| egl_error(name, "no such GL function"))
        };
        // SAFETY: each function has the signature OpenGL 3.0 gives it under that name.
        unsafe {
            Ok(Self {
                get_integer: std::mem::transmute::<extern "system" fn(), GetIntegerv>(find(
                    "glGetIntegerv",
                )?),
                gen_framebuffers: std::mem::transmute::<extern "system" fn(), GenObjects>(find(
                    "glGenFramebuffers",
                )?),
                delete_framebuffers: std::mem::transmute::<extern "system" fn(), DeleteObjects>(
                    find("glDeleteFramebuffers")?,
                ),
                bind_framebuffer: std::mem::transmute::<extern "system" fn(), BindObject>(find(
                    "glBindFramebuffer",
                )?),
                gen_renderbuffers: std::mem::transmute::<extern "system" fn(), GenObjects>(find(
                    "glGenRenderbuffers",
                )?),
                delete_renderbuffers: std::mem::transmute::<extern "system" fn(), DeleteObjects>(
                    find("glDeleteRenderbuffers")?,
                ),
                bind_renderbuffer: std::mem::transmute::<extern "system" fn(), BindObject>(find(
                    "glBindRenderbuffer",
                )?),
                renderbuffer_storage: std::mem::transmute::<
                    extern "system" fn(),
                    RenderbufferStorageMultisample,
                >(find("glRenderbufferStorageMultisample")?),
                framebuffer_renderbuffer: std::mem::transmute::<
                    extern "system" fn(),
                    FramebufferRenderbuffer,
                >(find("glFramebufferRenderbuffer")?),
                check_framebuffer_status: std::mem::transmute::<
                    extern "system" fn(),
                    CheckFramebufferStatus,
                >(find("glCheckFramebufferStatus")?),
            })
        }
    }
}

const GL_MAX_VIEWPORT_DIMS: u32 = 0x0D3A;
const GL_MAX_RENDERBUFFER_SIZE: u32 = 0x84E8;
const GL_MAX_SAMPLES: u32 = 0x8D57;
const GL_RENDERBUFFER: u32 = 0x8D41;
const GL_FRAMEBUFFER: u32 = 0x8D40;
const GL_FRAMEBUFFER_BINDING: u32 = 0x8CA6;
const GL_FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;
const GL_COLOR_ATTACHMENT0: u32 = 0x8CE0;
const GL_DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;
const GL_RGBA8: u32 = 0x8058;
const GL_DEPTH32F_STENCIL8: u32 = 0x8CAD;

/// What the OpenGL implementation can allocate for an offscreen framebuffer.
#[derive(Debug, Clone, Copy)]
pub(super) struct GlLimits {
    /// The largest width and height of a framebuffer: the smaller of the renderbuffer and viewport
    /// limits.
    pub(super) max_size: (u32, u32),
    /// The most multisampling samples a renderbuffer can have.
    pub(super) max_samples: u32,
}

/// libEGL, opened once and never closed: the EGL and Mesa libraries register per-thread
/// destructors, and unloading them while any thread still has one to run crashes that thread
/// when it exits.
static EGL: OnceLock<Result<Egl, RenderError>> = OnceLock::new();

fn egl_library() -> Result<&'static Egl, RenderError> {
    EGL.get_or_init(|| {
        // libEGL is opened globally so that MuJoCo's GL loader finds eglGetProcAddress.
        // SAFETY: loading libEGL runs only its initialisers, which have no preconditions.
        let library = unsafe { Library::open(Some("libEGL.so.1"), RTLD_NOW | RTLD_GLOBAL) }
            .map_err(|e| {
                egl_error(
                    "open libEGL.so.1 (Debian: apt-get install libegl1 libegl-mesa0)",
                    e,
                )
            })?;
        // SAFETY: the library is libEGL, whose symbols have the signatures khronos-egl declares.
        unsafe { Egl::load_required_from(library.into()) }
            .map_err(|e| egl_error("load the EGL 1.4 functions", e))
    })
    .as_ref()
    .map_err(Clone::clone)
}

thread_local! {
    /// The thread's OpenGL context while any renderer of the thread holds it.
    static THREAD_CONTEXT: RefCell<Weak<GlContext>> = const { RefCell::new(Weak::new()) };
}

/// An OpenGL (compatibility profile) context with no surface, current on the creating thread.
pub(super) struct GlContext {
    egl: &'static Egl,
    display: egl::Display,
    context: egl::Context,
    /// The OpenGL functions it is queried and checked with, looked up once.
    functions: GlFunctions,
}

impl GlContext {
    /// The calling thread's context, current: the one its other renderers hold, or a new one.
    /// Renderers of a thread share it because an OpenGL implementation compiles its shaders
    /// per context: on Mesa's llvmpipe a second renderer then starts in a fraction of the time.
    pub(super) fn for_this_thread() -> Result<Rc<Self>, RenderError> {
        THREAD_CONTEXT.with(|shared| {
            if let Some(gl) = shared.borrow().upgrade() {
                gl.make_current()?;
                return Ok(gl);
            }
            let gl = Rc::new(Self::new()?);
            *shared.borrow_mut() = Rc::downgrade(&gl);
            Ok(gl)
        })
    }

    fn new() -> Result<Self, RenderError> {
        let egl = egl_library()?;
        let functions = GlFunctions::load(egl)?;
        let display = open_display(egl)?;
        count_user(display.as_ptr() as usize, 1);
        let config = egl
            .choose_first_config(display, &CONFIG)
            .map_err(|e| egl_error("choose a config", e))?
            .ok_or_else(|| egl_error("choose a config", "no RGBA8 + depth24 pbuffer config"))?;
        egl.bind_api(egl::OPENGL_API)
            .map_err(|e| egl_error("bind the OpenGL API", e))?;
        let context = egl
            .create_context(display, config, None, &[egl::NONE])
            .map_err(|e| egl_error("create an OpenGL context", e))?;
        let gl = Self {
            egl,
            display,
            context,
            functions,
        };
        gl.make_current()?;
        Ok(gl)
    }

    /// The implementation's framebuffer limits, queried through this (current) context.
    pub(super) fn limits(&self) -> Result<GlLimits, RenderError> {
        let gl = &self.functions;
        self.make_current()?;
        let query = |name: u32| {
            let mut values = [0i32; 2];
            // SAFETY: this context is current; every queried name writes at most two integers.
            unsafe { (gl.get_integer)(name, values.as_mut_ptr()) };
            values.map(|v| u32::try_from(v).unwrap_or(0))
        };
        let renderbuffer = query(GL_MAX_RENDERBUFFER_SIZE)[0];
        let [viewport_width, viewport_height] = query(GL_MAX_VIEWPORT_DIMS);
        Ok(GlLimits {
            max_size: (
                renderbuffer.min(viewport_width),
                renderbuffer.min(viewport_height),
            ),
            max_samples: query(GL_MAX_SAMPLES)[0],
        })
    }

    /// Whether the implementation completes an offscreen framebuffer of `width` by `height`
    /// with `samples` samples, colour and depth-stencil, as MuJoCo makes it: some refuse buffers
    /// past a size in bytes that the size and sample limits do not tell (Mesa's llvmpipe: 1 GiB
    /// a buffer), and MuJoCo aborts the process on an incomplete framebuffer. The framebuffer
    /// is made, checked and deleted, and the one bound before is bound again.
    pub(super) fn completes(
        &self,
        width: u32,
        height: u32,
        samples: u32,
    ) -> Result<bool, RenderError> {
        self.make_current()?;
        let gl = &self.functions;
        let [width, height, samples] =
            [width, height, samples].map(|v| i32::try_from(v).unwrap_or(i32::MAX));
        let mut buffers = [0u32; 2];
        let mut framebuffer = 0u32;
        let mut bound = 0i32;
        // SAFETY: this context is current; the framebuffer and its buffers are generated,
        // bound, given storage, checked and deleted within it, and the framebuffer bound before
        // (read first) is bound again.
        let status = unsafe {
            (gl.get_integer)(GL_FRAMEBUFFER_BINDING, &mut bound);
            (gl.gen_framebuffers)(1, &mut framebuffer);
            (gl.bind_framebuffer)(GL_FRAMEBUFFER, framebuffer);
            (gl.gen_renderbuffers)(2, buffers.as_mut_ptr());
            let attachments = [
                (GL_RGBA8, GL_COLOR_ATTACHMENT0),
                (GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL_ATTACHMENT),
            ];
            for (buffer, (format, attachment)) in buffers.iter().zip(attachments) {
                (gl.bind_renderbuffer)(GL_RENDERBUFFER, *buffer);
                (gl.renderbuffer_storage)(GL_RENDERBUFFER, samples, format, width, height);
                (gl.framebuffer_renderbuffer)(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, *buffer);
            }
            let status = (gl.check_framebuffer_status)(GL_FRAMEBUFFER);
            (gl.bind_renderbuffer)(GL_RENDERBUFFER, 0);
            (gl.bind_framebuffer)(GL_FRAMEBUFFER, u32::try_from(bound).unwrap_or(0));
            (gl.delete_renderbuffers)(2, buffers.as_ptr());
            (gl.delete_framebuffers)(1, &framebuffer);
            status
        };
        Ok(status == GL_FRAMEBUFFER_COMPLETE)
    }

    /// Makes this context current on the calling thread (a no-op when it already is).
    pub(super) fn make_current(&self) -> Result<(), RenderError> {
        if self.egl.get_current_context() == Some(self.context) {
            return Ok(());
        }
        self.egl
            .make_current(self.display, None, None, Some(self.context))
            .map_err(|e| egl_error("make the context current", e))
    }
}

impl Drop for GlContext {
    fn drop(&mut self) {
        // The display stays initialised: it is shared by every context of the process.
        if self.egl.get_current_context() == Some(self.context) {
            let _released = self.egl.make_current(self.display, None, None, None);
        }
        count_user(self.display.as_ptr() as usize, -1);
        if let Err(error) = self.egl.destroy_context(self.display, self.context) {
            tracing::warn!(%error, "could not destroy the EGL context");
        }
    }
}

const CONFIG: [egl::Int; 15] = [
    egl::SURFACE_TYPE,
    egl::PBUFFER_BIT,
    egl::RENDERABLE_TYPE,
    egl::OPENGL_BIT,
    egl::RED_SIZE,
    8,
    egl::GREEN_SIZE,
    8,
    egl::BLUE_SIZE,
    8,
    egl::ALPHA_SIZE,
    8,
    egl::DEPTH_SIZE,
    24,
    egl::NONE,
];

/// `eglGetPlatformDisplayEXT`.
fn platform_display_function(egl: &Egl) -> Result<GetPlatformDisplay, RenderError> {
    egl.get_proc_address("eglGetPlatformDisplayEXT")
        // SAFETY: eglGetPlatformDisplayEXT has the GetPlatformDisplay signature (EGL_EXT_platform_base).
        .map(|f| unsafe { std::mem::transmute::<extern "system" fn(), GetPlatformDisplay>(f) })
        .ok_or_else(|| {
            egl_error(
                "find eglGetPlatformDisplayEXT",
                "EGL_EXT_platform_base missing",
            )
        })
}

/// The EGL display of an X11 connection, initialised.
///
/// # Safety
///
/// `x11` is an open Xlib `Display*` that outlives the returned display's use.
#[cfg(feature = "viewer")]
pub(super) unsafe fn x11_display(
    x11: *mut c_void,
) -> Result<(&'static Egl, egl::Display), RenderError> {
    const PLATFORM_X11: egl::Enum = 0x31D5;
    let egl = egl_library()?;
    let get_display = platform_display_function(egl)?;
    // SAFETY: the caller passes an open Xlib display; the attribute list is empty (null).
    let raw = unsafe { get_display(PLATFORM_X11, x11, std::ptr::null()) };
    if raw.is_null() {
        return Err(egl_error(
            "get the X11 display",
            "EGL_KHR_platform_x11 missing",
        ));
    }
    // SAFETY: `raw` is a non-null display handle just returned by EGL.
    let display = unsafe { egl::Display::from_ptr(raw) };
    egl.initialize(display)
        .map_err(|e| egl_error("initialise the X11 display", e))?;
    Ok((egl, display))
}

/// Every display worth trying, device platform first, and the first that initialises. When
/// every device is a software rasterizer (llvmpipe: no GPU), the least used display first, so
/// that two threads render in parallel; with a GPU, always the first.
fn open_display(egl: &Egl) -> Result<egl::Display, RenderError> {
    let get_display = platform_display_function(egl)?;
    let devices = devices(egl);
    let software_only = !devices.is_empty() && devices.iter().all(|d| is_software(egl, *d));
    let mut candidates: Vec<(egl::Enum, *mut c_void)> = devices
        .into_iter()
        .map(|device| (PLATFORM_DEVICE, device))
        .collect();
    candidates.push((PLATFORM_SURFACELESS_MESA, std::ptr::null_mut()));
    let mut displays = Vec::new();
    for (platform, native) in candidates {
        // SAFETY: `native` is a device handle from eglQueryDevicesEXT or null (the default
        // display), and the attribute list is empty (null).
        let raw = unsafe { get_display(platform, native, std::ptr::null()) };
        if !raw.is_null() && !displays.contains(&raw) {
            displays.push(raw);
        }
    }
    if software_only {
        displays.sort_by_key(|raw| display_users(*raw as usize));
    }
    let mut last_error = String::from("no EGL display");
    for raw in displays {
        // SAFETY: `raw` is a non-null display handle just returned by EGL.
        let display = unsafe { egl::Display::from_ptr(raw) };
        match egl.initialize(display) {
            Ok(_) => return Ok(display),
            Err(error) => last_error = error.to_string(),
        }
    }
    Err(egl_error(
        "initialise a device or surfaceless display",
        last_error,
    ))
}

/// Whether `device` is Mesa's software rasterizer (`EGL_MESA_device_software`).
fn is_software(egl: &Egl, device: *mut c_void) -> bool {
    let Some(query) = egl.get_proc_address("eglQueryDeviceStringEXT") else {
        return false;
    };
    // SAFETY: eglQueryDeviceStringEXT has the QueryDeviceString signature (EGL_EXT_device_query).
    let query = unsafe { std::mem::transmute::<extern "system" fn(), QueryDeviceString>(query) };
    // SAFETY: `device` is a handle from eglQueryDevicesEXT; EGL_EXTENSIONS is a valid name.
    let extensions = unsafe { query(device, EXTENSIONS) };
    if extensions.is_null() {
        return false;
    }
    // SAFETY: EGL returns a NUL-terminated string it owns for the process's life.
    let extensions = unsafe { CStr::from_ptr(extensions) };
    extensions
        .to_string_lossy()
        .split_whitespace()
        .any(|extension| extension == "EGL_MESA_device_software")
}

fn devices(egl: &Egl) -> Vec<*mut c_void> {
    let Some(query) = egl.get_proc_address("eglQueryDevicesEXT") else {
        return Vec::new();
    };
    // SAFETY: eglQueryDevicesEXT has the QueryDevices signature (EGL_EXT_device_enumeration).
    let query = unsafe { std::mem::transmute::<extern "system" fn(), QueryDevices>(query) };
    let mut devices = [std::ptr::null_mut(); MAX_DEVICES];
    let mut count: egl::Int = 0;
    // SAFETY: the array holds MAX_DEVICES handles and `count` is writable.
    let ok = unsafe { query(MAX_DEVICES as egl::Int, devices.as_mut_ptr(), &mut count) };
    if ok != egl::TRUE {
        return Vec::new();
    }
    devices[..usize::try_from(count).unwrap_or(0).min(MAX_DEVICES)].to_vec()
}

pub(super) fn egl_error(step: &'static str, reason: impl ToString) -> RenderError {
    RenderError::Egl {
        step,
        reason: reason.to_string(),
    }
}
