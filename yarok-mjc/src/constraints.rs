//! What holds a joint back: the constraint forces of the last step on one degree of freedom —
//! contacts, equality constraints, joint and tendon limits, dry friction — each by its source.

use std::collections::BTreeMap;

use crate::contacts::ContactPoint;
use crate::data::Data;
use crate::model::{GeomId, JointId, TendonId, to_usize};
use crate::{ObjectKind, sys};

/// Where a constraint force comes from.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ConstraintSource {
    /// A contact between two geoms, pressed together with `normal_force` newtons.
    Contact {
        /// The two geoms, in MuJoCo's order.
        geoms: [GeomId; 2],
        /// Their bodies' names (a body without a name as `body N`, its index).
        bodies: [String; 2],
        /// The normal force the contact carries (newtons).
        normal_force: f64,
    },
    /// An equality constraint (a weld, a connect, a joint or tendon coupling).
    Equality {
        /// Its index among the model's equality constraints.
        index: usize,
        /// Its name, if it has one.
        name: Option<String>,
    },
    /// A joint at (or within the margin of) one of its limits.
    JointLimit {
        /// The joint.
        joint: JointId,
        /// Its name, if it has one.
        name: Option<String>,
    },
    /// A tendon at (or within the margin of) one of its limits.
    TendonLimit {
        /// The tendon.
        tendon: TendonId,
        /// Its name, if it has one.
        name: Option<String>,
    },
    /// Dry friction (`frictionloss`) of a joint's degree of freedom or a tendon.
    Friction,
}

/// One source's share of the constraint force on a degree of freedom.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintForce {
    /// What exerts it.
    pub source: ConstraintSource,
    /// The generalised force (N·m on a hinge, N on a slide) it puts on the degree of freedom.
    pub force: f64,
}

impl Data {
    /// The constraint forces of the last step (or [`Data::forward`]) on degree of freedom `dof`
    /// ([`Data::dof`]), one per source that puts a force on it (a contact's rows, an equality
    /// constraint's rows summed), the strongest first. Their sum is MuJoCo's
    /// `qfrc_constraint[dof]`.
    ///
    /// # Panics
    ///
    /// When `dof` is not below the model's `nv`.
    #[track_caller]
    pub fn constraint_forces_on(&self, dof: usize) -> Vec<ConstraintForce> {
        let nv = self.model().nv();
        assert!(dof < nv, "degree of freedom {dof} of a model with {nv}");
        let raw = self.ffi();
        let nefc = usize::try_from(raw.nefc).unwrap_or(0);
        if nefc == 0 {
            return Vec::new();
        }
        // SAFETY: after a step, efc_type, efc_id and efc_force hold nefc entries.
        let (types, ids, forces) = unsafe {
            (
                std::slice::from_raw_parts(raw.efc_type, nefc),
                std::slice::from_raw_parts(raw.efc_id, nefc),
                std::slice::from_raw_parts(raw.efc_force, nefc),
            )
        };
        let mut rows_of: BTreeMap<(i32, i32), Vec<usize>> = BTreeMap::new();
        for row in 0..nefc {
            rows_of.entry((types[row], ids[row])).or_default().push(row);
        }
        let contacts = self.contacts();
        let mut masked = vec![0.0; nefc];
        let mut generalised = vec![0.0; nv];
        let mut found: Vec<ConstraintForce> = rows_of
            .into_iter()
            .filter_map(|((kind, id), rows)| {
                masked.fill(0.0);
                for &row in &rows {
                    masked[row] = forces[row];
                }
                // SAFETY: model and data belong together; `generalised` holds nv numbers and
                // `masked` nefc, as mj_mulJacTVec reads and writes.
                unsafe {
                    self.model().mj().mj_mulJacTVec(
                        self.model().raw(),
                        raw,
                        generalised.as_mut_ptr(),
                        masked.as_ptr(),
                    );
                }
                let force = generalised[dof];
                let source = self.source(kind, to_usize(id), &contacts)?;
                (force != 0.0).then_some(ConstraintForce { source, force })
            })
            .collect();
        found.sort_by(|a, b| b.force.abs().total_cmp(&a.force.abs()));
        found
    }

    /// The source of the constraint rows of type `kind` and id `id`.
    fn source(&self, kind: i32, id: usize, contacts: &[ContactPoint]) -> Option<ConstraintSource> {
        let model = self.model();
        Some(match kind as sys::mjtConstraint {
            sys::mjCNSTR_EQUALITY => ConstraintSource::Equality {
                index: id,
                name: model.name_of(ObjectKind::Equality, id),
            },
            sys::mjCNSTR_LIMIT_JOINT => ConstraintSource::JointLimit {
                joint: JointId::at(model, id),
                name: model.name_of(ObjectKind::Joint, id),
            },
            sys::mjCNSTR_LIMIT_TENDON => ConstraintSource::TendonLimit {
                tendon: TendonId::at(model, id),
                name: model.name_of(ObjectKind::Tendon, id),
            },
            sys::mjCNSTR_CONTACT_FRICTIONLESS
            | sys::mjCNSTR_CONTACT_PYRAMIDAL
            | sys::mjCNSTR_CONTACT_ELLIPTIC => {
                let contact = contacts.get(id)?;
                let body_name = |geom: GeomId| {
                    let body = model.geom_body(geom);
                    model
                        .body_name(body)
                        .unwrap_or_else(|| format!("body {}", body.index()))
                };
                ConstraintSource::Contact {
                    geoms: contact.geoms,
                    bodies: contact.geoms.map(body_name),
                    normal_force: contact.normal_force,
                }
            }
            _ => ConstraintSource::Friction,
        })
    }
}
