//! yarok-components: the components that ship with yarok.
//!
//! Its one job is the catalogue: cameras, the DIGIT, GelSight and GelTip tactile sensors and
//! their optical models, the UR5 arm, the Robotiq 2F-85 gripper, the Anet A30 printer used as a
//! cartesian robot, worlds and toys, each with one interface per environment.
//!
pub mod cameras;
pub mod robots;
pub mod tactile;
pub mod toys;
pub mod worlds;

use yarok_core::compose::ComponentType;

/// Every bundled component, for tools that pick components by tag at run time.
pub fn catalogue() -> Vec<ComponentType> {
    vec![
        ComponentType::of::<worlds::EmptyWorld>(),
        ComponentType::of::<worlds::PrinterWorld>(),
        ComponentType::of::<worlds::TowerWorld>(),
        ComponentType::of::<cameras::Cam>(),
        ComponentType::of::<robots::AnetA30>(),
        ComponentType::of::<toys::TumbleTower>(),
    ]
}
