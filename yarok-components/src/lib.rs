//! yarok-components: the components that ship with yarok.
//!
//! Its one job is the catalogue of components, each with one interface per environment. Today:
//! a camera ([`cameras::Cam`]), the optical models of the DIGIT, GelSight and GelTip tactile
//! sensors ([`tactile`]), the Anet A30 printer used as a cartesian robot ([`robots::AnetA30`]),
//! the UR5 and UR5e arms with their closed-form kinematics ([`robots::ur`]), the Robotiq
//! 2F-85 gripper ([`grippers::Robotiq2f85`]), a tumble tower
//! ([`toys::TumbleTower`]) and worlds ([`worlds`]), each world with behaviours that show it at
//! work ([`demos`]); plugins that record runs ([`plugins`]). [`nalgebra`] is re-exported for
//! poses.
//!
pub use nalgebra;
/// The Zenoh API the bridge is built on (feature `zenoh`), for clients in the same program.
#[cfg(feature = "zenoh")]
pub use zenoh;

pub mod cameras;
pub mod demos;
pub mod features;
pub mod grippers;
pub(crate) mod model_cameras;
pub mod plugins;
pub mod probe_images;
pub mod robots;
pub mod tactile;
pub mod tactile_sensors;
pub mod toys;
pub mod worlds;

use yarok_core::component::ComponentType;

/// A world from a template file a user wrote, which may use every bundled component by its tag
/// (as `yarok compose FILE` and Python's `yarok.World(FILE)` compose it).
pub fn template_world(path: impl AsRef<std::path::Path>) -> yarok_core::component::Declaration {
    catalogue().into_iter().fold(
        yarok_core::component::Declaration::new("world").template_file(path.as_ref()),
        |world, component| world.uses_type(component),
    )
}

/// Every bundled component, for tools that pick components by tag at run time.
pub fn catalogue() -> Vec<ComponentType> {
    vec![
        ComponentType::of::<worlds::EmptyWorld>(),
        ComponentType::of::<worlds::PrinterWorld>(),
        ComponentType::of::<worlds::TowerWorld>(),
        ComponentType::of::<worlds::PickAndPlaceWorld>(),
        ComponentType::of::<worlds::DigitWorld>(),
        ComponentType::of::<worlds::GelTipWorld>(),
        ComponentType::of::<cameras::Cam>(),
        ComponentType::of::<robots::AnetA30>(),
        ComponentType::of::<robots::ur::Ur5>(),
        ComponentType::of::<robots::ur::Ur5e>(),
        ComponentType::of::<grippers::Robotiq2f85>(),
        ComponentType::of::<tactile_sensors::Digit>(),
        ComponentType::of::<tactile_sensors::GelSight2014>(),
        ComponentType::of::<tactile_sensors::GelTip>(),
        ComponentType::of::<toys::TumbleTower>(),
        ComponentType::of::<toys::Block>(),
        ComponentType::of::<toys::Spot>(),
        ComponentType::of::<toys::Rope>(),
    ]
}
