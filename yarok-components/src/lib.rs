//! yarok-components: the components that ship with yarok.
//!
//! Its one job is the catalogue: cameras, the DIGIT, GelSight and GelTip tactile sensors and
//! their optical models, the UR5 arm, the Robotiq 2F-85 gripper, the Anet A30 printer used as a
//! cartesian robot, worlds and toys, each with one interface per environment.
//!
//! This crate is being built up issue by issue; today it holds the toys.

pub mod toys;

use yarok_core::compose::ComponentType;

/// Every bundled component, for tools that pick components by tag at run time.
pub fn catalogue() -> Vec<ComponentType> {
    vec![ComponentType::of::<toys::TumbleTower>()]
}
