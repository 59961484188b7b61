//! What differs between the UR arms yarok models: DH parameters, link masses, centres of mass
//! and inertias, and where the upper arm and forearm run along the shoulder axis. One template
//! (`ur.xml`) takes them as defaults, so the MJCF and the kinematics share one source.

use std::f64::consts::FRAC_PI_2;

use nalgebra::Point3;
use yarok_core::component::Declaration;

use super::kinematics::DhParameters;

/// Position servo gains `(kp, kv)` of the three big joints (N·m/rad, N·m·s/rad) and of the
/// wrists. With gravity compensated, they hold a pose within 1e-3 rad and, with velocity
/// feed-forward, track `movel` lines within millimetres.
pub(crate) const GAINS: [(f64, f64); 2] = [(5000.0, 400.0), (1500.0, 60.0)];

/// Where the arms start: upright, clear of a table they stand on.
const UPRIGHT: [f64; 6] = [0.0, -FRAC_PI_2, 0.0, -FRAC_PI_2, 0.0, 0.0];

/// What differs between the UR arms yarok models.
#[derive(Debug)]
pub struct ArmModel {
    pub(crate) tag: &'static str,
    pub(crate) dh: DhParameters,
    /// Link masses (kg), shoulder to wrist 3.
    masses: [f64; 6],
    /// Centres of mass in each link's DH frame (the frame on the next joint's axis), metres.
    coms: [[f64; 3]; 6],
    /// Principal moments of inertia about the centre of mass (kg·m²), in the body's axes.
    inertias: [[f64; 3]; 6],
    /// Offsets along the shoulder axis of the upper arm's and the forearm's tubes (metres).
    offsets: [f64; 2],
}

/// Centres of mass shared by both arms (UR's DH article), in the DH frames.
const COMS: [[f64; 3]; 6] = [
    [0.0, -0.02561, 0.00193],
    [0.2125, 0.0, 0.11336],
    [0.15, 0.0, 0.0265],
    [0.0, -0.0018, 0.01634],
    [0.0, 0.0018, 0.01634],
    [0.0, 0.0, -0.001159],
];

/// The UR5e's inertia diagonals from Universal Robots' ROS 2 description (products of inertia,
/// all below 1.4e-3 kg·m², left out).
const UR5E_INERTIAS: [[f64; 3]; 6] = [
    [0.0070021, 0.00648091, 0.00657286],
    [0.01505885, 0.33388086, 0.33247207],
    [0.00399632, 0.07879254, 0.0784851],
    [0.00165491, 0.00135962, 0.00126279],
    [0.00135617, 0.00127827, 0.00096614],
    [0.00018694, 0.00018908, 0.00025756],
];

const UR5E_MASSES: [f64; 6] = [3.761, 8.058, 2.846, 1.37, 1.3, 0.365];
const UR5_MASSES: [f64; 6] = [3.7, 8.393, 2.33, 1.219, 1.219, 0.1879];

pub(super) const UR5E: ArmModel = ArmModel {
    tag: "ur5e",
    dh: DhParameters::UR5E,
    masses: UR5E_MASSES,
    coms: COMS,
    inertias: UR5E_INERTIAS,
    offsets: [0.138, 0.007],
};

/// UR publishes no inertias for the UR5 (CB3): the UR5e's, scaled by the links' mass ratios.
pub(super) const UR5: ArmModel = ArmModel {
    tag: "ur5",
    dh: DhParameters::UR5,
    masses: UR5_MASSES,
    coms: COMS,
    inertias: UR5E_INERTIAS,
    offsets: [0.13585, 0.0165],
};

impl ArmModel {
    pub(crate) fn declaration(&self) -> Declaration {
        let dh = self.dh;
        let coms: [[f64; 3]; 6] = std::array::from_fn(|i| {
            // The body of joint i is DH frame i−1 turned by θi; link i's frame sits at its
            // fixed offset from there.
            let com = dh.link_offset(i) * Point3::from(self.coms[i]);
            [com.x, com.y, com.z]
        });
        let inertias: [[f64; 3]; 6] = std::array::from_fn(|i| {
            let scale = self.masses[i] / UR5E_MASSES[i];
            self.inertias[i].map(|moment| moment * scale)
        });
        Declaration::new(self.tag)
            .template(include_str!("ur.xml"))
            .config(UrConfig {
                d1: dh.d1,
                a2: dh.a2,
                a3: dh.a3,
                d4: dh.d4,
                d5: dh.d5,
                d6: dh.d6,
                masses: self.masses,
                coms,
                inertias,
                offsets: self.offsets,
                kp: GAINS.map(|(kp, _)| kp),
                kv: GAINS.map(|(_, kv)| kv),
                tcp: [0.0; 6],
                start: UPRIGHT,
                pos: [0.0; 3],
                quat: [1.0, 0.0, 0.0, 0.0],
            })
    }
}

/// An arm's config: the model's geometry and masses its template builds from, the servo
/// gains, the TCP, where it starts and where its base is.
#[derive(serde::Serialize, serde::Deserialize)]
pub(super) struct UrConfig {
    d1: f64,
    a2: f64,
    a3: f64,
    d4: f64,
    d5: f64,
    d6: f64,
    masses: [f64; 6],
    coms: [[f64; 3]; 6],
    inertias: [[f64; 3]; 6],
    offsets: [f64; 2],
    pub(super) kp: [f64; 2],
    pub(super) kv: [f64; 2],
    pub(super) tcp: [f64; 6],
    pub(super) start: [f64; 6],
    pos: [f64; 3],
    quat: [f64; 4],
}
