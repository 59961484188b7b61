//! Universal Robots arms: the UR5 (CB3) and the UR5e, their closed-form kinematics, and motions
//! with the meaning of the controller's `movej`, `movel` and `stopj`.

mod arm;
mod config;
mod controller;
mod drive;
mod error;
mod kinematics;
mod measured;
mod mock;
mod model;
mod motion;
mod path;
mod payload;
mod real;
mod sim;

use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces, Mock};
use yarok_mjc::Sim;

pub use arm::{ARRIVED_M, Arm, MOVE_J_DEFAULTS, MOVE_L_DEFAULTS};
pub use config::{ArmConfig, ArmNames};
pub use controller::{ARRIVED_RAD, SETTLE_SECONDS};
pub use drive::{ArmDrive, Order, Setpoint};
pub use error::MotionError;
pub use kinematics::{
    DhParameters, IkError, JointLimits, Joints, Kinematics, Solutions, pose_from_vector,
    pose_to_vector,
};
pub use measured::{MeasuredKinematics, isometry_of};
pub use motion::Move;
pub use path::PathError;
pub use payload::Payload;

use model::ArmModel;

/// The arm's settings from its tag: servo gains and the TCP.
fn config<E: yarok_core::component::Environment>(
    bind: &Bind<E>,
    model: &ArmModel,
) -> Result<ArmConfig, BindError> {
    let kp: [f64; 2] = bind.config_value("kp")?;
    let kv: [f64; 2] = bind.config_value("kv")?;
    let tcp: [f64; 6] = bind.config_value("tcp")?;
    let start: Joints = bind.config_value("start")?;
    if kp
        .iter()
        .chain(&kv)
        .any(|gain| !(*gain > 0.0 && gain.is_finite()))
    {
        return Err(bind.error(format!(
            "servo gains kp {kp:?} and kv {kv:?} must be positive"
        )));
    }
    let kinematics = Kinematics::new(model.dh).with_tcp(pose_from_vector(tcp));
    Ok(ArmConfig {
        kinematics,
        names: ArmNames::YAROK,
        start: Some(start),
    })
}

macro_rules! arm_component {
    ($(#[$doc:meta])* $name:ident, $model:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone)]
        pub struct $name(Arm);

        impl std::ops::Deref for $name {
            type Target = Arm;

            fn deref(&self) -> &Arm {
                &self.0
            }
        }

        impl Component for $name {
            fn declaration() -> Declaration {
                $model.declaration()
            }

            fn interfaces(interfaces: &mut Interfaces<Self>) {
                interfaces.add::<Sim>().add::<Mock>().add::<yarok_hw::Real>();
            }
        }

        impl Interface<yarok_hw::Real> for $name {
            fn check(bind: &Bind<yarok_hw::Real>) -> Result<(), BindError> {
                config(bind, &$model)?;
                real::settings(bind).map(drop)
            }

            async fn bind(bind: &mut Bind<yarok_hw::Real>) -> Result<Self, BindError> {
                let config = config(bind, &$model)?;
                Arm::bind_real(bind, config.kinematics).await.map($name)
            }
        }

        impl Interface<Sim> for $name {
            async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
                let config = config(bind, &$model)?;
                Arm::bind_sim(bind, config).map($name)
            }
        }

        impl Interface<Mock> for $name {
            async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
                let config = config(bind, &$model)?;
                let start = config.start.unwrap_or_default();
                Ok($name(Arm::bind_mock(bind, config.kinematics, start)))
            }
        }
    };
}

arm_component! {
    /// A Universal Robots UR5e: six joints on the UR5e's DH frames, its link masses, position
    /// servos with gravity compensation; an [`Arm`] (it derefs to one).
    ///
    /// Tag `ur5e`; config `pos` and `quat` (the base frame in the parent's), `start` (joint
    /// angles at the start of a run, default upright: `[0, -π/2, 0, -π/2, 0, 0]`), `tcp` (UR pose
    /// vector of the TCP in the flange frame, default 0), `kp` and `kv` (servo gains of the big
    /// joints and of the wrists). Tools attach to the
    /// body `flange` (`<robotiq_2f85 name="gripper" parent="flange"/>`); the site `flange`
    /// is the controller's tool0.
    ///
    /// Environments: `sim`; `mock` (follows its motions exactly); `real`: the arm through its
    /// controller (interface settings `host`, `rtde_hz`, `reply_seconds`,
    /// `connect_seconds`) — motions sent as URScript `movej`/`movel`, joints read over RTDE,
    /// the controller's kinematics checked against the UR5e's at connect.
    Ur5e, model::UR5E
}

arm_component! {
    /// A Universal Robots UR5 (CB3, series 3 kinematics): as [`Ur5e`] with the UR5's DH
    /// parameters and masses. Tag `ur5`.
    Ur5, model::UR5
}
