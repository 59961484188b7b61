//! [`MeasuredKinematics`]: a UR model's DH parameters, base frame and flange, measured from the
//! frames MuJoCo compiled, so that the closed form agrees with the model exactly whatever
//! lengths its author rounded to.

use std::sync::Arc;

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use yarok_core::component::{Bind, BindError};
use yarok_mjc::{Data, JointId, Model, Pose, Sim, SiteId};

use super::config::ArmNames;
use super::kinematics::{DhParameters, Joints, Kinematics};

/// How far (metres, radians) the model may be from a UR chain and its closed form from the
/// model's flange.
const TOLERANCE: f64 = 1e-6;

/// A UR model's kinematics as MuJoCo compiled it: its DH parameters and the flange site in
/// `tool0`'s frame ([`Kinematics::tcp`]), and where its base frame is in the world.
///
/// # Examples
///
/// ```
/// use std::sync::Arc;
///
/// use yarok_components::robots::ur::{ArmNames, DhParameters, MeasuredKinematics, Ur5e};
/// use yarok_mjc::Model;
///
/// let composition = yarok_core::compose::compose::<Ur5e>()?;
/// let model = Arc::new(Model::from_composition(&composition)?);
/// let joints = ArmNames::YAROK.joints.map(|name| model.joint(name).unwrap());
/// let measured = MeasuredKinematics::measure(&model, &joints, model.site("flange")?)?;
/// // yarok's UR5e is built from the UR5e's DH parameters.
/// assert!((measured.kinematics.dh.d4 - DhParameters::UR5E.d4).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredKinematics {
    /// The DH parameters, the default joint limits, and the flange site as the TCP.
    pub kinematics: Kinematics,
    /// The DH base frame in the world, as the model starts.
    pub base: Isometry3<f64>,
}

impl MeasuredKinematics {
    /// Measures the arm whose six joints (base to wrist 3) are `joints` and whose flange (the
    /// real arm's `tool0`, or the site a tool attaches at) is `flange`: the joints' axes at zero
    /// give the DH parameters; the base frame lies on the first axis, level with the origin of
    /// the body that carries the arm; the flange site, expressed in `tool0`'s frame, becomes the
    /// TCP. The closed form is then checked against MuJoCo's flange at several configurations.
    ///
    /// # Errors
    ///
    /// When the chain is not a UR's (axes that should meet or be parallel are not, a joint
    /// turns the other way) or the closed form misses MuJoCo's flange by more than 1e-6.
    pub fn measure(
        model: &Arc<Model>,
        joints: &[JointId; 6],
        flange: SiteId,
    ) -> Result<Self, String> {
        let mut data = Data::new(model).map_err(|e| e.to_string())?;
        set(&mut data, joints, &[0.0; 6]);
        let axes: [(Point3<f64>, Vector3<f64>); 6] = joints.map(|joint| {
            let (anchor, axis) = data.joint_axis(joint);
            (Point3::from(anchor), Vector3::from(axis).normalize())
        });
        let carrier = data.body_pose(model.body_parent(model.joint_body(joints[0])));
        let site = isometry_of(&data.site_pose(flange));
        let (dh, base) = chain(
            &axes,
            Point3::from(carrier.pos),
            Point3::from(site.translation.vector),
        )?;
        let tcp = (base * dh.forward(&[0.0; 6])).inverse() * site;
        let measured = Self {
            kinematics: Kinematics::new(dh).with_tcp(tcp),
            base,
        };
        measured.check(&mut data, joints, flange)?;
        Ok(measured)
    }

    /// [`MeasuredKinematics::measure`] on the model being bound: the joints and flange site of
    /// `names`, as the component's template names them.
    ///
    /// # Errors
    ///
    /// [`BindError`] when a name is missing or the measure fails.
    pub fn of(bind: &Bind<Sim>, names: &ArmNames) -> Result<Self, BindError> {
        use yarok_mjc::SimBind;
        let mut joints = Vec::with_capacity(6);
        for name in names.joints {
            joints.push(bind.joint(name)?.id());
        }
        let joints: [JointId; 6] = joints.try_into().map_err(|_| bind.error("six joints"))?;
        let flange = bind.site(names.flange)?.id();
        Self::measure(bind.backend().model(), &joints, flange)
            .map_err(|reason| bind.error(format!("its kinematics: {reason}")))
    }

    /// Compares the closed form with MuJoCo's flange at zero and at spread configurations.
    fn check(&self, data: &mut Data, joints: &[JointId; 6], flange: SiteId) -> Result<(), String> {
        let configurations: [Joints; 4] = [
            [0.0; 6],
            [0.3, -1.1, 1.4, -0.9, 0.7, -2.1],
            [-2.5, -2.0, -1.0, 1.3, -1.6, 0.4],
            [1.7, 0.6, 2.2, 2.9, 2.4, 3.0],
        ];
        for q in configurations {
            set(data, joints, &q);
            let site = isometry_of(&data.site_pose(flange));
            let ours = self.base * self.kinematics.forward(&q);
            let position = (site.translation.vector - ours.translation.vector).norm();
            let angle = site.rotation.angle_to(&ours.rotation);
            if position > TOLERANCE || angle > TOLERANCE {
                return Err(format!(
                    "a UR's closed form from its axes misses its flange by {position:.2e} m and \
                     {angle:.2e} rad at {q:?} (a joint turns the other way from a UR's, or its \
                     zero is elsewhere)"
                ));
            }
        }
        Ok(())
    }
}

/// Sets the joints to `q` and computes the poses.
fn set(data: &mut Data, joints: &[JointId; 6], q: &Joints) {
    for (joint, angle) in joints.iter().zip(q) {
        data.qpos_mut(*joint)[0] = *angle;
    }
    data.forward();
}

/// A pose MuJoCo reports ([`Pose`]) as an isometry, in the frame MuJoCo gives it in.
///
/// ```
/// use yarok_components::robots::ur::isometry_of;
/// use yarok_mjc::Pose;
///
/// let pose = Pose { pos: [0.1, 0.2, 0.3], quat: [1.0, 0.0, 0.0, 0.0] };
/// assert_eq!(isometry_of(&pose).translation.vector.z, 0.3);
/// ```
pub fn isometry_of(pose: &Pose) -> Isometry3<f64> {
    let [w, x, y, z] = pose.quat;
    Isometry3::from_parts(
        Translation3::from(Vector3::from(pose.pos)),
        UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)),
    )
}

/// The DH parameters and base frame of a UR chain whose joint axes at zero are `axes` (a point
/// on each, its direction), the base level with `carrier` (the origin of the body carrying the
/// arm), `tool0` level with `flange` along the last axis.
fn chain(
    axes: &[(Point3<f64>, Vector3<f64>); 6],
    carrier: Point3<f64>,
    flange: Point3<f64>,
) -> Result<(DhParameters, Isometry3<f64>), String> {
    let [first, second, third, fourth, fifth, sixth] = axes;
    let base_origin = first.0 + first.1 * (carrier - first.0).dot(&first.1);
    let shoulder = meeting(first, second, "1 and 2")?;
    let upper_arm = offset(second, third, "2 and 3")?;
    let forearm = offset(third, fourth, "3 and 4")?;
    let wrist_1 = shoulder + upper_arm + forearm;
    let wrist_2 = meeting(fourth, fifth, "4 and 5")?;
    let wrist_3 = meeting(fifth, sixth, "5 and 6")?;
    // The arm stretches along −x at zero: x is away from the upper arm's reach.
    let x = -upper_arm.normalize();
    if x.dot(&first.1).abs() > TOLERANCE
        || upper_arm.normalize().dot(&forearm.normalize()) < 1.0 - TOLERANCE
    {
        return Err("the upper arm and forearm do not stretch level from the first axis".into());
    }
    let dh = DhParameters {
        d1: (shoulder - base_origin).dot(&first.1),
        a2: -upper_arm.norm(),
        a3: -forearm.norm(),
        d4: (wrist_2 - wrist_1).dot(&fourth.1),
        d5: (wrist_3 - wrist_2).dot(&fifth.1),
        d6: (flange - wrist_3).dot(&sixth.1),
    };
    let rotation = UnitQuaternion::from_basis_unchecked(&[x, first.1.cross(&x), first.1]);
    let base = Isometry3::from_parts(Translation3::from(base_origin.coords), rotation);
    Ok((dh, base))
}

/// Where two axes that should meet do.
fn meeting(
    (p, u): &(Point3<f64>, Vector3<f64>),
    (q, v): &(Point3<f64>, Vector3<f64>),
    which: &str,
) -> Result<Point3<f64>, String> {
    let across = u.dot(v);
    let parallel = 1.0 - across * across;
    if parallel < TOLERANCE {
        return Err(format!("axes {which} are parallel, not crossing"));
    }
    let w = p - q;
    let s = (across * v.dot(&w) - u.dot(&w)) / parallel;
    let t = (v.dot(&w) - across * u.dot(&w)) / parallel;
    let (on_first, on_second) = (p + u * s, q + v * t);
    let gap = (on_first - on_second).norm();
    if gap > TOLERANCE {
        return Err(format!(
            "axes {which} pass {gap:.2e} m apart instead of meeting"
        ));
    }
    Ok(on_first)
}

/// The offset across two axes that should be parallel, from the first to the second.
fn offset(
    (p, u): &(Point3<f64>, Vector3<f64>),
    (q, v): &(Point3<f64>, Vector3<f64>),
    which: &str,
) -> Result<Vector3<f64>, String> {
    if u.cross(v).norm() > TOLERANCE || u.dot(v) < 0.0 {
        return Err(format!("axes {which} are not parallel"));
    }
    let w = q - p;
    Ok(w - u * w.dot(u))
}
