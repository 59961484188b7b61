//! Drawing only what a camera is for: a scene's geoms whose bounding spheres come within a reach
//! of the eye, or only those that can touch a given geom. A tactile sensor's camera sees a few
//! millimetres into its gel, and only what can press into it; everything else in the world would
//! cost vertex work or draw what the gel cannot feel (markers, visual meshes).

use crate::{GeomId, Model, ObjectKind, sys};

/// Keeps in `scene` only the geoms that may come within `reach` metres of its camera, keeping
/// their order.
pub(super) fn keep_within(scene: &mut sys::mjvScene, reach: f64) {
    // The scene holds a stereo pair of eyes, each half the model's interpupillary distance to
    // one side; a mono render draws from their midpoint.
    let [left, right] = scene.camera.map(|eye| eye.pos.map(f64::from));
    let eye = std::array::from_fn(|axis| (left[axis] + right[axis]) / 2.0);
    keep(scene, |geom| reaches(geom, eye, reach));
}

/// Keeps in `scene` only the model's geoms that could touch `touched`: their `contype` and
/// `conaffinity` match its, and they are neither on its body nor on the body it is mounted on
/// (its parent). No sites, decorations or visual-only geoms.
pub(super) fn keep_touching(scene: &mut sys::mjvScene, model: &Model, touched: GeomId) {
    let own = model.geom_body(touched);
    let mount = model.body_parent(own);
    let touched = model.index_of(touched);
    let ngeom = model.count(ObjectKind::Geom);
    keep(scene, |geom| {
        geom.objtype == sys::mjOBJ_GEOM as i32
            && usize::try_from(geom.objid).is_ok_and(|id| {
                id < ngeom && model.types_match(id, touched) && {
                    let body = model.geom_body(GeomId::at(model, id));
                    body != own && (body != mount || mount.index() == 0)
                }
            })
    });
}

/// Keeps in `scene` the geoms `wanted` accepts, in their order.
fn keep(scene: &mut sys::mjvScene, wanted: impl Fn(&sys::mjvGeom) -> bool) {
    let count = usize::try_from(scene.ngeom).unwrap_or(0);
    if count == 0 || scene.geoms.is_null() {
        return;
    }
    // SAFETY: mjv_updateScene filled the first `ngeom` entries of the scene's geom array, which
    // the scene owns and nothing else borrows during this call.
    let geoms = unsafe { std::slice::from_raw_parts_mut(scene.geoms, count) };
    let mut kept = 0;
    for index in 0..count {
        if wanted(&geoms[index]) {
            geoms.swap(kept, index);
            kept += 1;
        }
    }
    scene.ngeom = i32::try_from(kept).unwrap_or(i32::MAX);
}

/// Whether any point of `geom` may lie within `reach` of `eye`: planes by their distance, other
/// geoms by their bounding sphere (the model's, or one around their size when they have none).
fn reaches(geom: &sys::mjvGeom, eye: [f64; 3], reach: f64) -> bool {
    let offset: [f64; 3] = std::array::from_fn(|axis| f64::from(geom.pos[axis]) - eye[axis]);
    if geom.type_ == sys::mjGEOM_PLANE as i32 {
        let normal = [geom.mat[2], geom.mat[5], geom.mat[8]].map(f64::from);
        let height: f64 = offset.iter().zip(normal).map(|(o, n)| o * n).sum();
        return height.abs() <= reach;
    }
    let radius = if geom.modelrbound > 0.0 {
        f64::from(geom.modelrbound)
    } else {
        geom.size
            .iter()
            .map(|s| f64::from(*s).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let distance = offset.iter().map(|o| o * o).sum::<f64>().sqrt();
    distance - radius <= reach
}

#[cfg(test)]
mod tests {
    use super::reaches;
    use crate::sys;

    fn geom(kind: u32, pos: [f32; 3], rbound: f32) -> sys::mjvGeom {
        sys::mjvGeom {
            type_: kind as i32,
            pos,
            mat: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
            modelrbound: rbound,
            size: [0.01; 3],
            ..Default::default()
        }
    }

    #[test]
    fn a_geom_reaches_by_its_bounding_sphere_and_a_plane_by_its_height() {
        let eye = [0.0, 0.0, 0.1];
        let sphere = geom(sys::mjGEOM_SPHERE, [0.0, 0.0, 0.13], 0.005);
        assert!(reaches(&sphere, eye, 0.026));
        assert!(!reaches(&sphere, eye, 0.024));
        let far_plane = geom(sys::mjGEOM_PLANE, [5.0, 5.0, 0.0], 0.0);
        assert!(reaches(&far_plane, eye, 0.11));
        assert!(!reaches(&far_plane, eye, 0.09));
        let decor = geom(sys::mjGEOM_BOX, [0.0, 0.05, 0.1], 0.0);
        assert!(reaches(&decor, eye, 0.035));
        assert!(!reaches(&decor, eye, 0.03));
    }
}
