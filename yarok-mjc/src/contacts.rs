//! Contacts: which geoms may touch (MuJoCo's collision filter), and the contacts the last step
//! found, with the forces they carry.

use crate::data::Data;
use crate::model::{GeomId, Model, to_usize};
use crate::{ObjectKind, sys};

/// A contact between two geoms after the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// The two geoms in contact, in MuJoCo's order (the normal points from the first to the
    /// second).
    pub geoms: [GeomId; 2],
    /// The contact's position in world coordinates (metres), midway between the surfaces.
    pub position: [f64; 3],
    /// The contact normal in world coordinates, from the first geom to the second.
    pub normal: [f64; 3],
    /// Signed distance between the surfaces (metres): negative when they interpenetrate.
    pub distance: f64,
    /// The normal force the geoms press on each other with (newtons, ≥ 0 when pushing).
    pub normal_force: f64,
}

impl Model {
    /// The body a geom belongs to.
    ///
    /// # Panics
    ///
    /// When `geom` was resolved in a different model.
    #[track_caller]
    pub fn geom_body(&self, geom: GeomId) -> crate::BodyId {
        let index = self.index_of(geom);
        // SAFETY: geom_bodyid holds ngeom entries and `index` < ngeom.
        let body = unsafe { self.array(self.raw().geom_bodyid, self.count(ObjectKind::Geom)) };
        crate::BodyId::at(self, to_usize(body[index]))
    }

    /// Whether MuJoCo's collision filter lets geoms `a` and `b` touch: their `contype` and
    /// `conaffinity` match, they are on different bodies that are not welded together, and
    /// neither body is the other's parent (unless that is the world; MuJoCo's default
    /// `filterparent`). Explicit `<contact><exclude>` pairs are not consulted.
    ///
    /// # Panics
    ///
    /// When a geom was resolved in a different model.
    #[track_caller]
    pub fn can_collide(&self, a: GeomId, b: GeomId) -> bool {
        let (a, b) = (self.index_of(a), self.index_of(b));
        self.geoms_can_collide(a, b)
    }

    /// [`Model::can_collide`] by geom index (both below `ngeom`).
    pub(crate) fn geoms_can_collide(&self, a: usize, b: usize) -> bool {
        let m = self.raw();
        let (ngeom, nbody) = (self.count(ObjectKind::Geom), self.count(ObjectKind::Body));
        // SAFETY: the geom arrays hold ngeom entries, the body arrays nbody; a, b < ngeom and
        // body ids < nbody.
        let (geom_body, weld, parent) = unsafe {
            (
                self.array(m.geom_bodyid, ngeom),
                self.array(m.body_weldid, nbody),
                self.array(m.body_parentid, nbody),
            )
        };
        if !self.types_match(a, b) {
            return false;
        }
        let [body_a, body_b] = [a, b].map(|g| to_usize(weld[to_usize(geom_body[g])]));
        if body_a == body_b {
            return false;
        }
        let filter_parent = m.opt.disableflags & sys::mjDSBL_FILTERPARENT as i32 == 0;
        let parent_of = |body: usize| to_usize(weld[to_usize(parent[body])]);
        let related = (parent_of(body_a) == body_b && body_b != 0)
            || (parent_of(body_b) == body_a && body_a != 0);
        !(filter_parent && related)
    }

    /// Whether geoms `a` and `b` (indices below `ngeom`) have matching `contype` and
    /// `conaffinity`: the part of MuJoCo's filter that is the geoms' own.
    pub(crate) fn types_match(&self, a: usize, b: usize) -> bool {
        let m = self.raw();
        let ngeom = self.count(ObjectKind::Geom);
        // SAFETY: geom_contype and geom_conaffinity hold ngeom entries; a, b < ngeom.
        let (contype, conaffinity) = unsafe {
            (
                self.array(m.geom_contype, ngeom),
                self.array(m.geom_conaffinity, ngeom),
            )
        };
        contype[a] & conaffinity[b] != 0 || contype[b] & conaffinity[a] != 0
    }
}

impl Data {
    /// The contacts the last step (or [`Data::forward`]) found, with their normal forces.
    pub fn contacts(&self) -> Vec<ContactPoint> {
        let count = usize::try_from(self.ffi().ncon).unwrap_or(0);
        let contacts = if count == 0 || self.ffi().contact.is_null() {
            &[][..]
        } else {
            // SAFETY: `contact` holds ncon entries after a step or forward, and lives as long
            // as this borrow of the data.
            unsafe { std::slice::from_raw_parts(self.ffi().contact, count) }
        };
        contacts
            .iter()
            .enumerate()
            .filter(|(_, contact)| contact.geom1 >= 0 && contact.geom2 >= 0)
            .map(|(index, contact)| {
                let mut force = [0.0; 6];
                // SAFETY: model and data are this state's; `index` < ncon; `force` holds the 6
                // numbers mj_contactForce writes.
                unsafe {
                    self.model().mj().mj_contactForce(
                        self.model().raw(),
                        self.ffi(),
                        index as i32,
                        force.as_mut_ptr(),
                    );
                }
                let geom = |id: i32| GeomId::at(self.model(), to_usize(id));
                ContactPoint {
                    geoms: [geom(contact.geom1), geom(contact.geom2)],
                    position: contact.pos,
                    normal: [contact.frame[0], contact.frame[1], contact.frame[2]],
                    distance: contact.dist,
                    normal_force: force[0],
                }
            })
            .collect()
    }
}
