//! [`Block`]: a cube to pick and place, and [`Spot`]: a marked place on a surface.

use yarok_core::BoxError;
use yarok_core::component::{
    Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, Mock,
};
use yarok_hw::Real;
use yarok_mjc::{Body, Joint, Sim, SimBind, Site};

/// A cube of side `size` metres (default 0.04) and `mass` kilograms (default 0.1), free to move,
/// its centre placed at `pos`; colour `rgba`.
///
/// Tag `block`. Environments: `sim` (where it is, and it can be put elsewhere); `mock` and
/// `real` (where it was placed: on real hardware, where you measured the real block to be).
#[derive(Debug, Clone)]
pub struct Block {
    size: f64,
    body: Option<(Body, Joint)>,
    placed: [f64; 3],
}

impl Block {
    /// The side of the cube in metres.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// Where its centre is in the world (metres).
    pub fn position(&self) -> [f64; 3] {
        self.body
            .as_ref()
            .map_or(self.placed, |(body, _)| body.pose().pos)
    }

    /// Puts it at rest with its centre at `position` (metres, world frame), turned `yaw`
    /// radians about the vertical: where an episode starts it.
    ///
    /// # Errors
    ///
    /// Outside `sim`, where a real block is moved by hand.
    pub fn place(&self, position: [f64; 3], yaw: f64) -> Result<(), BoxError> {
        let Some((_, joint)) = &self.body else {
            return Err("a block is placed by hand outside `sim`".into());
        };
        let half = yaw / 2.0;
        joint.set_free_pose(position, [half.cos(), 0.0, 0.0, half.sin()])?;
        Ok(())
    }
}

/// The block's config.
#[derive(serde::Serialize, serde::Deserialize)]
struct BlockConfig {
    size: f64,
    mass: f64,
    pos: [f64; 3],
    rgba: [f64; 4],
}

impl Component for Block {
    fn declaration() -> Declaration {
        Declaration::new("block")
            .config(BlockConfig {
                size: 0.04,
                mass: 0.1,
                pos: [0.0, 0.0, 0.02],
                rgba: [0.8, 0.3, 0.2, 1.0],
            })
            .template(
                r#"<mujoco>
                  <worldbody>
                    <body name="block" pos="{pos}">
                      <freejoint name="block"/>
                      <geom name="block" type="box" size="{size / 2} {size / 2} {size / 2}" mass="{mass}"
                            rgba="{rgba}" friction="1 0.05 0.001" condim="4"/>
                    </body>
                  </worldbody>
                </mujoco>"#,
            )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>().add::<Real>();
    }
}

impl Interface<Sim> for Block {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Ok(Block {
            body: Some((bind.body("block")?, bind.joint("block")?)),
            ..Block::placed(bind)?
        })
    }
}

impl Block {
    /// A block where its config places it.
    fn placed<E: Environment>(bind: &Bind<E>) -> Result<Self, BindError> {
        let BlockConfig { size, pos, .. } = bind.config()?;
        Ok(Block {
            size,
            body: None,
            placed: pos,
        })
    }
}

impl Interface<Mock> for Block {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Block::placed(bind)
    }
}

impl Interface<Real> for Block {
    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        Block::placed(bind)
    }
}

/// A place marked on a surface: a flat disc of `radius` metres (default 0.05) whose centre is
/// at `pos`; it collides with nothing.
///
/// Tag `spot`. Environments: `sim`; `mock` and `real` (where it was placed).
#[derive(Debug, Clone)]
pub struct Spot {
    site: Option<Site>,
    placed: [f64; 3],
}

impl Spot {
    /// Where its centre is in the world (metres).
    pub fn position(&self) -> [f64; 3] {
        self.site
            .as_ref()
            .map_or(self.placed, |site| site.pose().pos)
    }
}

/// The spot's config.
#[derive(serde::Serialize, serde::Deserialize)]
struct SpotConfig {
    radius: f64,
    pos: [f64; 3],
}

impl Component for Spot {
    fn declaration() -> Declaration {
        Declaration::new("spot")
            .config(SpotConfig {
                radius: 0.05,
                pos: [0.0; 3],
            })
            .template(
                r#"<mujoco>
                  <worldbody>
                    <geom name="spot" type="cylinder" size="{radius} 0.0005" pos="{pos}"
                          contype="0" conaffinity="0" rgba="0.2 0.75 0.3 0.6"/>
                    <site name="spot" pos="{pos}" size="0.002"/>
                  </worldbody>
                </mujoco>"#,
            )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>().add::<Real>();
    }
}

impl Interface<Sim> for Spot {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Ok(Spot {
            site: Some(bind.site("spot")?),
            ..Spot::placed(bind)?
        })
    }
}

impl Spot {
    /// A spot where its config places it.
    fn placed<E: Environment>(bind: &Bind<E>) -> Result<Self, BindError> {
        let SpotConfig { pos, .. } = bind.config()?;
        Ok(Spot {
            site: None,
            placed: pos,
        })
    }
}

impl Interface<Mock> for Spot {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Spot::placed(bind)
    }
}

impl Interface<Real> for Spot {
    async fn bind(bind: &mut Bind<Real>) -> Result<Self, BindError> {
        Spot::placed(bind)
    }
}
