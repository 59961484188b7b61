//! MuJoCo's visualisation structures, made alike for every renderer: a scene with its options,
//! and a rendering context.

use crate::{Model, sys};

/// A scene of up to `max_geoms` geoms for `model`, with MuJoCo's default options and
/// perturbation; shadows and reflections off unless `shadows`.
pub(super) fn make_scene(
    model: &Model,
    max_geoms: i32,
    shadows: bool,
) -> (Box<sys::mjvScene>, sys::mjvOption, sys::mjvPerturb) {
    let mut scene = Box::<sys::mjvScene>::default();
    let mut option = sys::mjvOption::default();
    let mut perturb = sys::mjvPerturb::default();
    let mj = model.mj();
    // SAFETY: the structs are owned and writable; the model is valid.
    unsafe {
        mj.mjv_defaultOption(&mut option);
        mj.mjv_defaultPerturb(&mut perturb);
        mj.mjv_defaultScene(&mut *scene);
        mj.mjv_makeScene(model.raw(), &mut *scene, max_geoms);
    }
    if !shadows {
        scene.flags[sys::mjRND_SHADOW as usize] = 0;
        scene.flags[sys::mjRND_REFLECTION as usize] = 0;
    }
    (scene, option, perturb)
}

/// Fills `scene` with `data`'s state seen by `camera`, every category of geom.
///
/// # Safety
///
/// `model`, `data`, `option`, `perturb`, `camera` and `scene` are valid and belong to the
/// same model.
pub(super) unsafe fn update_scene(
    model: &Model,
    data: &mut crate::Data,
    option: &sys::mjvOption,
    perturb: &sys::mjvPerturb,
    camera: &mut sys::mjvCamera,
    scene: &mut sys::mjvScene,
) {
    // SAFETY: as the caller guarantees.
    unsafe {
        model.mj().mjv_updateScene(
            model.raw(),
            data.raw_mut_ptr(),
            option,
            perturb,
            camera,
            sys::mjCAT_ALL as i32,
            scene,
        );
    }
}

/// How a rendering context is made: its offscreen buffer, and what it uploads.
#[derive(Debug, Clone, Copy)]
pub(super) struct ContextSpec {
    /// The offscreen buffer's width and height.
    pub(super) offscreen: (u32, u32),
    /// Keep the model's multisampling of the offscreen buffer (else none).
    pub(super) multisampling: bool,
    /// Upload the model's textures.
    pub(super) textures: bool,
    /// `mjFONTSCALE_…`.
    pub(super) font_scale: sys::mjtFontScale,
    /// The buffer drawn into: `mjFB_WINDOW` or `mjFB_OFFSCREEN`.
    pub(super) buffer: sys::mjtFramebuffer,
}

impl ContextSpec {
    /// The model `mjr_makeContext` is given: a shallow copy of `model` (sharing its arrays,
    /// only read) asking for this offscreen buffer and these uploads.
    pub(super) fn context_model(&self, model: &Model) -> sys::mjModel {
        let mut context_model = *model.raw();
        context_model.vis.global.offwidth = i32::try_from(self.offscreen.0).unwrap_or(i32::MAX);
        context_model.vis.global.offheight = i32::try_from(self.offscreen.1).unwrap_or(i32::MAX);
        if !self.multisampling {
            context_model.vis.quality.offsamples = 0;
        }
        if !self.textures {
            context_model.ntex = 0;
        }
        context_model
    }

    /// A rendering context for `model` as this spec says, bound to its buffer.
    ///
    /// # Safety
    ///
    /// An OpenGL context is current on this thread, and can make the offscreen buffer
    /// (MuJoCo aborts when it cannot).
    pub(super) unsafe fn make(&self, model: &Model) -> Box<sys::mjrContext> {
        let context_model = self.context_model(model);
        let mut context = Box::<sys::mjrContext>::default();
        let mj = model.mj();
        // SAFETY: the caller's GL context is current; the context is owned and writable;
        // `context_model` is a valid mjModel for the call.
        unsafe {
            mj.mjr_defaultContext(&mut *context);
            mj.mjr_makeContext(&context_model, &mut *context, self.font_scale as i32);
            mj.mjr_setBuffer(self.buffer as i32, &mut *context);
        }
        context
    }
}
