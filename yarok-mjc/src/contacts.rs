//! Contacts: whether two geoms' collision types match, and the contacts the last step found,
//! with the forces they carry.

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

    /// Whether geoms `a` and `b` (indices below `ngeom`) have matching `contype` and
    /// `conaffinity`: the part of MuJoCo's filter that is the geoms' own.
    #[cfg(feature = "render")]
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
        self.contacts_where(|_| true)
    }

    /// The contacts the last step found that `geom` is in, with their normal forces.
    ///
    /// # Panics
    ///
    /// When `geom` was resolved in a different model.
    #[track_caller]
    pub fn contacts_of(&self, geom: GeomId) -> Vec<ContactPoint> {
        let index = i32::try_from(self.model().index_of(geom)).unwrap_or(-1);
        self.contacts_where(|contact| contact.geom1 == index || contact.geom2 == index)
    }

    /// The contacts `wanted` accepts, their forces computed for those alone.
    fn contacts_where(&self, wanted: impl Fn(&sys::mjContact) -> bool) -> Vec<ContactPoint> {
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
            .filter(|(_, contact)| contact.geom1 >= 0 && contact.geom2 >= 0 && wanted(contact))
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
