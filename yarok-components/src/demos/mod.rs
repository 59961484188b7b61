//! Demos: for each bundled world, behaviours that show it at work — what `yarok run WORLD`
//! runs, and what the examples run. Each is a plain `async fn(Pl)`: read them as examples of
//! writing behaviours.
//!
//! # Examples
//!
//! ```no_run
//! use yarok_components::demos;
//!
//! let demo = demos::find("digit_world").expect("a bundled world");
//! let feel = demo.behaviour(None).expect("a default behaviour");
//! assert_eq!(feel.name, "feel");
//! // `yarok run digit_world --set behaviour/out="shots"`, in code:
//! let platform = yarok_core::runtime::Platform::builder()
//!     .world_type(demo.world)
//!     .set(r#"behaviour/out="shots""#);
//! ```

mod digit_world;
mod geltip_world;
mod idle;
mod pick_and_place;
mod printer_world;
mod tactile_rig;

use std::future::Future;
use std::pin::Pin;

use yarok_core::BoxError;
use yarok_core::component::{Component, ComponentType};
use yarok_core::runtime::{BehaviourResult, Pl, PlatformBuilder};
use yarok_core::value::Value;

pub use digit_world::{START_REGION, START_YAW, demonstrate, feel};
pub use geltip_world::pull;
pub use idle::idle;
pub use pick_and_place::{stack, stack_with};
pub use printer_world::survey;
pub use tactile_rig::{INDEX_HEADER, collect, grid, press};

use crate::worlds::{
    DigitWorld, EmptyWorld, GelTipWorld, PickAndPlaceWorld, PrinterWorld, TactileRigWorld,
    TowerWorld,
};

/// A demo's behaviour: its name, what runs, and its settings' defaults.
#[derive(Debug, Clone, Copy)]
pub struct DemoBehaviour {
    /// Its name (`stack`).
    pub name: &'static str,
    /// The behaviour.
    pub run: fn(Pl) -> Pin<Box<dyn Future<Output = BehaviourResult>>>,
    /// Its settings (`[behaviour]`) and their defaults, as TOML values (`out` = `"out"`).
    pub defaults: &'static [(&'static str, &'static str)],
}

impl DemoBehaviour {
    /// `builder` running this behaviour, its settings' defaults declared.
    pub fn install(&self, builder: PlatformBuilder) -> PlatformBuilder {
        let builder = self.defaults.iter().fold(builder, |builder, (key, value)| {
            builder.behaviour_default(key, Value::from_text(value))
        });
        builder.behaviour_named(self.name, self.run)
    }
}

/// A bundled world and the behaviours that show it.
#[derive(Debug, Clone, Copy)]
pub struct Demo {
    /// The world.
    pub world: ComponentType,
    /// Its behaviours, the default first.
    pub behaviours: &'static [DemoBehaviour],
}

impl Demo {
    fn of<W: Component>(behaviours: &'static [DemoBehaviour]) -> Self {
        Self {
            world: ComponentType::of::<W>(),
            behaviours,
        }
    }

    /// The world's tag (`pick_and_place_world`).
    pub fn tag(&self) -> String {
        self.world.declaration().tag().to_owned()
    }

    /// The behaviour `name`, or the default one when `name` is `None`.
    pub fn behaviour(&self, name: Option<&str>) -> Option<DemoBehaviour> {
        match name {
            Some(name) => self.behaviours.iter().find(|b| b.name == name).copied(),
            None => self.behaviours.first().copied(),
        }
    }
}

const IDLE: DemoBehaviour = DemoBehaviour {
    name: "idle",
    run: |pl| Box::pin(idle(pl)),
    defaults: &[("seconds", "2.0")],
};

/// The setting of demos that save images: the folder.
const OUT: &[(&str, &str)] = &[("out", "\"out\"")];

/// Every bundled world with its demos.
pub fn demos() -> Vec<Demo> {
    vec![
        Demo::of::<EmptyWorld>(&[IDLE]),
        Demo::of::<TowerWorld>(&[IDLE]),
        Demo::of::<PrinterWorld>(&[
            DemoBehaviour {
                name: "survey",
                run: |pl| Box::pin(survey(pl)),
                defaults: OUT,
            },
            IDLE,
        ]),
        Demo::of::<PickAndPlaceWorld>(&[
            DemoBehaviour {
                name: "stack",
                run: |pl| Box::pin(stack(pl)),
                defaults: &[],
            },
            IDLE,
        ]),
        Demo::of::<DigitWorld>(&[
            DemoBehaviour {
                name: "feel",
                run: |pl| Box::pin(feel(pl)),
                defaults: OUT,
            },
            DemoBehaviour {
                name: "demonstrate",
                run: |pl| Box::pin(demonstrate(pl)),
                defaults: &[("episodes", "10"), ("seed", "0")],
            },
            IDLE,
        ]),
        Demo::of::<GelTipWorld>(&[
            DemoBehaviour {
                name: "pull",
                run: |pl| Box::pin(pull(pl)),
                defaults: OUT,
            },
            IDLE,
        ]),
        Demo::of::<TactileRigWorld>(&[
            DemoBehaviour {
                name: "press",
                run: |pl| Box::pin(press(pl)),
                defaults: OUT,
            },
            DemoBehaviour {
                name: "collect",
                run: |pl| Box::pin(collect(pl)),
                defaults: &[
                    ("out", "\"out/tactile_rig\""),
                    ("points", "5"),
                    ("spacing_mm", "2.0"),
                    ("depths_mm", "[0.5, 1.0, 1.5]"),
                ],
            },
        ]),
    ]
}

/// The demo of the world tagged `tag`.
pub fn find(tag: &str) -> Option<Demo> {
    demos().into_iter().find(|demo| demo.tag() == tag)
}

/// The folder a demo saves images in: the behaviour's setting `out`, created.
fn out_folder(pl: &Pl) -> Result<String, BoxError> {
    let out = pl
        .config()
        .get("out")
        .and_then(|out| out.as_str())
        .ok_or("behaviour/out must be a folder")?;
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {out}: {e}"))?;
    Ok(out.to_owned())
}
