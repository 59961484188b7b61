//! [`Rope`]: a rope lying on a surface, a chain of capsules held end to end.

use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces, Mock};
use yarok_mjc::{Body, Sim, SimBind};

/// A rope of `segments` capsules (default 20) of `length` metres each (default 0.02) and
/// `radius` (default 0.006), each free and held to the next end to end by a point constraint
/// (a chain needs no nesting this way); it lies straight along +x from `pos` (its first
/// segment's centre).
///
/// Tag `rope`. Environments: `sim` (where its ends are); `mock` (where they were placed).
#[derive(Debug, Clone)]
pub struct Rope {
    ends: Option<[Body; 2]>,
    placed: [[f64; 3]; 2],
}

impl Rope {
    /// Where its first and last segments' centres are (metres, world frame).
    pub fn ends(&self) -> [[f64; 3]; 2] {
        match &self.ends {
            Some([first, last]) => [first.pose().pos, last.pose().pos],
            None => self.placed,
        }
    }
}

/// The rope's config.
#[derive(serde::Serialize, serde::Deserialize)]
struct RopeConfig {
    segments: i64,
    length: f64,
    radius: f64,
    pos: [f64; 3],
}

impl Component for Rope {
    fn declaration() -> Declaration {
        Declaration::new("rope")
            .config(RopeConfig {
                segments: 20,
                length: 0.02,
                radius: 0.006,
                pos: [0.0, 0.0, 0.006],
            })
            .template(
                r#"<mujoco>
                  <default>
                    <default class="segment">
                      <geom type="capsule" size="{radius}" fromto="{-length / 2} 0 0 {length / 2} 0 0"
                            mass="0.01" rgba="0.85 0.6 0.3 1" friction="1 0.01 0.001" condim="4"/>
                    </default>
                  </default>
                  <worldbody>
                    <for each="range(segments)" as="i">
                      <body name="segment_{i}" pos="{pos[0] + i * length} {pos[1]} {pos[2]}" childclass="segment">
                        <freejoint/>
                        <geom class="segment"/>
                      </body>
                    </for>
                  </worldbody>
                  <equality>
                    <for each="range(1, segments)" as="i">
                      <connect body1="segment_{i - 1}" body2="segment_{i}" anchor="{length / 2} 0 0"
                               solref="0.005 1"/>
                    </for>
                  </equality>
                  <contact>
                    <for each="range(1, segments)" as="i">
                      <exclude body1="segment_{i - 1}" body2="segment_{i}"/>
                    </for>
                  </contact>
                </mujoco>"#,
            )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>();
    }
}

fn placed<E: yarok_core::component::Environment>(
    bind: &Bind<E>,
) -> Result<[[f64; 3]; 2], BindError> {
    let RopeConfig {
        segments,
        length,
        pos,
        ..
    } = bind.config()?;
    let last = [
        pos[0] + (segments - 1).max(0) as f64 * length,
        pos[1],
        pos[2],
    ];
    Ok([pos, last])
}

impl Interface<Sim> for Rope {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let RopeConfig { segments, .. } = bind.config()?;
        if segments < 2 {
            return Err(bind.error(format!("a rope needs at least 2 segments, not {segments}")));
        }
        let last = format!("segment_{}", segments - 1);
        Ok(Rope {
            ends: Some([bind.body("segment_0")?, bind.body(&last)?]),
            placed: placed(bind)?,
        })
    }
}

impl Interface<Mock> for Rope {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Ok(Rope {
            ends: None,
            placed: placed(bind)?,
        })
    }
}
