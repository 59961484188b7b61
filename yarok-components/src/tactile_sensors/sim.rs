//! A tactile sensor in `sim`: its internal camera renders the depth of what can touch its gel,
//! and MuJoCo's contacts on the gel say how hard it is pressed.

use yarok_core::component::{Bind, BindError};
use yarok_mjc::{Body, Camera, DepthImage, Geom, RenderPreset, Sim, SimBind};

use super::kind::SensorKind;
use super::modelled::{GelSensing, Modelled, Touch};
use super::sensor::TactileSensor;

/// The sensor's internal camera, its gel and its body.
struct SimSensing {
    camera: Camera,
    gel: Geom,
    body: Body,
}

impl GelSensing for SimSensing {
    fn see(&self, depth: &mut DepthImage) -> Result<(), String> {
        self.camera.depth_into(depth).map_err(|e| e.to_string())
    }

    fn touches(&self) -> Vec<Touch> {
        let pose = self.body.pose();
        let origin = pose.to_local([0.0; 3]);
        self.gel
            .contacts()
            .into_iter()
            .map(|contact| {
                // The normal points from the gel to what touches it; the push is the other way.
                let normal = pose.to_local(contact.normal.map(|n| -n));
                Touch {
                    position: pose.to_local(contact.position),
                    push: std::array::from_fn(|axis| normal[axis] - origin[axis]),
                    normal_force: contact.normal_force,
                }
            })
            .collect()
    }
}

impl TactileSensor {
    /// Binds a sensor of `kind` in `sim`: its internal camera renders depth with the depth
    /// preset, only of geoms that can touch the gel and can reach it.
    pub(super) fn bind_sim(kind: &dyn SensorKind, bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let (width, height) = kind.size();
        let gel = bind.geom(kind.gel())?;
        let camera = bind
            .camera_with("camera", width, height, RenderPreset::Depth)?
            .touching(&gel)
            .within(kind.reach());
        let body = bind.body("sensor")?;
        Modelled::bind(kind, bind, Box::new(SimSensing { camera, gel, body }))
    }
}
