//! [`UrArm`]: the component over an [`Arm`] for one UR model; [`Ur5e`] and [`Ur5`].

use std::marker::PhantomData;

use yarok_core::component::{
    Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, Mock,
};
use yarok_hw::Real;
use yarok_mjc::Sim;

use super::model::{ArmModel, UR5, UR5E, UrConfig};
use super::{Arm, ArmConfig, ArmNames, Kinematics, pose_from_vector, real};

/// One Universal Robots model: its name, and the DH parameters, masses and inertias its
/// template and kinematics share. Implemented by [`Ur5eModel`] and [`Ur5Model`].
pub trait UrModel: Clone + std::fmt::Debug + 'static {
    /// The name messages give the arm's type (`Ur5e`).
    const NAME: &'static str;
    /// The model.
    #[doc(hidden)]
    const MODEL: ArmModel;
}

/// The UR5e (e-Series).
#[derive(Debug, Clone, Copy)]
pub struct Ur5eModel;

impl UrModel for Ur5eModel {
    const NAME: &'static str = "Ur5e";
    const MODEL: ArmModel = UR5E;
}

/// The UR5 (CB3).
#[derive(Debug, Clone, Copy)]
pub struct Ur5Model;

impl UrModel for Ur5Model {
    const NAME: &'static str = "Ur5";
    const MODEL: ArmModel = UR5;
}

/// A Universal Robots arm of model `M`: six joints on its DH frames, its link masses, position
/// servos with gravity compensation; an [`Arm`] (it derefs to one).
///
/// Config `pos` and `quat` (the base frame in the parent's), `start` (joint angles at the start
/// of a run, default upright: `[0, -π/2, 0, -π/2, 0, 0]`), `tcp` (UR pose vector of the TCP in
/// the flange frame, default 0), `kp` and `kv` (servo gains of the big joints and of the
/// wrists). Tools attach to the body `flange` (`<robotiq_2f85 name="gripper"
/// parent="flange"/>`); the site `flange` is the controller's tool0.
///
/// Environments: `sim`; `mock` (follows its motions exactly); `real`: the arm through its
/// controller (interface settings `host`, `rtde_hz`, `reply_seconds`, `connect_seconds`) —
/// motions sent as URScript `movej`/`movel`, joints read over RTDE, the controller's
/// kinematics checked against the model's at connect.
#[derive(Debug, Clone)]
pub struct UrArm<M>(Arm, PhantomData<M>);

/// A Universal Robots UR5e; tag `ur5e`.
pub type Ur5e = UrArm<Ur5eModel>;

/// A Universal Robots UR5 (CB3, series 3 kinematics), with the UR5's DH parameters and masses;
/// tag `ur5`.
pub type Ur5 = UrArm<Ur5Model>;

impl<M> std::ops::Deref for UrArm<M> {
    type Target = Arm;

    fn deref(&self) -> &Arm {
        &self.0
    }
}

impl<M> UrArm<M> {
    fn new(arm: Arm) -> Self {
        Self(arm, PhantomData)
    }
}

impl<M: UrModel> Component for UrArm<M> {
    fn declaration() -> Declaration {
        M::MODEL.declaration()
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>().add::<Real>();
    }

    fn type_name() -> &'static str {
        M::NAME
    }
}

/// The arm's config from its tag: servo gains, the TCP and where it starts.
fn config<M: UrModel, E: Environment>(bind: &Bind<E>) -> Result<ArmConfig, BindError> {
    let UrConfig {
        kp, kv, tcp, start, ..
    } = bind.config()?;
    if kp
        .iter()
        .chain(&kv)
        .any(|gain| !(*gain > 0.0 && gain.is_finite()))
    {
        return Err(bind.error(format!(
            "servo gains kp {kp:?} and kv {kv:?} must be positive"
        )));
    }
    let kinematics = Kinematics::new(M::MODEL.dh).with_tcp(pose_from_vector(tcp));
    Ok(ArmConfig {
        kinematics,
        names: ArmNames::YAROK,
        start: Some(start),
    })
}

impl<M: UrModel> Interface<Real> for UrArm<M> {
    fn check(bind: &Bind<Real>) -> Result<(), BindError> {
        config::<M, _>(bind)?;
        real::settings(bind).map(drop)
    }

    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        let config = config::<M, _>(bind)?;
        Arm::bind_real(bind, config.kinematics).await.map(Self::new)
    }
}

impl<M: UrModel> Interface<Sim> for UrArm<M> {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let config = config::<M, _>(bind)?;
        Arm::bind_sim(bind, config).map(Self::new)
    }
}

impl<M: UrModel> Interface<Mock> for UrArm<M> {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        let config = config::<M, _>(bind)?;
        let start = config.start.unwrap_or_default();
        Ok(Self::new(Arm::bind_mock(bind, config.kinematics, start)))
    }
}
