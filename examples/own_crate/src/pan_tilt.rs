//! A pan-tilt camera mount of your own that carries one of yarok's bundled components: two
//! hinges turned by position servos, and a `Cam` on the tilt link looking along it. In `sim`
//! MuJoCo turns the links; in `mock` the links are where they are told to be, and the camera
//! renders the world as declared with them there, so a vision behaviour runs in both.

use std::rc::Rc;

use yarok::components::cameras::Cam;
use yarok::mjc::{Joint, MockBind};
use yarok::prelude::*;

/// A pan-tilt mount: `point(pan, tilt)` (radians), `angles()`, and its camera, `eye()`.
#[derive(Clone)]
pub struct PanTilt {
    axes: Rc<dyn Axes>,
    eye: Cam,
}

impl std::fmt::Debug for PanTilt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PanTilt")
            .field("angles", &self.angles())
            .finish()
    }
}

/// How the two axes turn in one environment.
trait Axes {
    fn point(&self, pan: f64, tilt: f64);
    fn angles(&self) -> (f64, f64);
}

/// In `sim`: the servos turn the links; the joints say where they are.
struct Servos {
    pan: Actuator,
    tilt: Actuator,
    joints: [Joint; 2],
}

impl Axes for Servos {
    fn point(&self, pan: f64, tilt: f64) {
        self.pan.set(pan);
        self.tilt.set(tilt);
    }

    fn angles(&self) -> (f64, f64) {
        (self.joints[0].position(), self.joints[1].position())
    }
}

/// In `mock`: the declared world's joints are set where they are told (no physics), which is
/// what the mock camera renders.
struct Placed {
    joints: [Joint; 2],
}

impl Axes for Placed {
    fn point(&self, pan: f64, tilt: f64) {
        self.joints[0].set_position(pan);
        self.joints[1].set_position(tilt);
    }

    fn angles(&self) -> (f64, f64) {
        (self.joints[0].position(), self.joints[1].position())
    }
}

/// The mount's config: where it stands (`pos`, metres, in its parent's frame).
#[derive(Clone, serde::Serialize, serde::Deserialize)]
struct PanTiltConfig {
    pos: [f64; 3],
}

impl Component for PanTilt {
    fn declaration() -> Declaration {
        Declaration::new("pan_tilt")
            .config(PanTiltConfig {
                pos: [0.0, 0.0, 0.0],
            })
            .uses::<Cam>()
            .template(
                r#"<mujoco>
                     <compiler angle="radian"/>
                     <!-- The mount's parts touch nothing: its base is welded to the world, and
                          MuJoCo's parent filter does not keep the pan link off such a base. -->
                     <default><geom contype="0" conaffinity="0"/></default>
                     <worldbody>
                       <body name="base" pos="{pos}">
                         <geom type="cylinder" size="0.03 0.01" pos="0 0 0.01" mass="0.3"/>
                         <body name="pan_link" pos="0 0 0.03">
                           <joint name="pan" axis="0 0 1" range="-1.5 1.5" armature="0.005"/>
                           <geom type="box" size="0.015 0.015 0.015" mass="0.05"/>
                           <body name="tilt_link" pos="0 0 0.03">
                             <joint name="tilt" axis="0 1 0" range="-1 1" armature="0.005"/>
                             <geom type="box" size="0.03 0.01 0.01" mass="0.03"/>
                             <body pos="0.04 0 0">
                               <cam name="eye" width="96" height="72" look="+x"/>
                             </body>
                           </body>
                         </body>
                       </body>
                     </worldbody>
                     <actuator>
                       <position name="pan_servo" joint="pan" kp="2" kv="0.15"/>
                       <position name="tilt_servo" joint="tilt" kp="2" kv="0.15"/>
                     </actuator>
                   </mujoco>"#,
            )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Mock>();
    }
}

impl Interface<Sim> for PanTilt {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let servos = Servos {
            pan: bind.actuator("pan_servo")?,
            tilt: bind.actuator("tilt_servo")?,
            joints: [bind.joint("pan")?, bind.joint("tilt")?],
        };
        Ok(PanTilt {
            axes: Rc::new(servos),
            eye: bind.child::<Cam>("eye")?,
        })
    }
}

impl Interface<Mock> for PanTilt {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        let placed = Placed {
            joints: [bind.declared_joint("pan")?, bind.declared_joint("tilt")?],
        };
        Ok(PanTilt {
            axes: Rc::new(placed),
            eye: bind.child::<Cam>("eye")?,
        })
    }
}

impl PanTilt {
    /// Turns the mount to `pan` (about its vertical axis, positive to the left) and `tilt`
    /// (positive down), radians.
    pub fn point(&self, pan: f64, tilt: f64) {
        self.axes.point(pan, tilt);
    }

    /// Where the mount is turned, `(pan, tilt)` in radians.
    pub fn angles(&self) -> (f64, f64) {
        self.axes.angles()
    }

    /// Its camera.
    pub fn eye(&self) -> &Cam {
        &self.eye
    }
}

/// A post with the mount on top, and a red block on the floor off to the left.
#[derive(Debug)]
pub struct Lookout;

impl Component for Lookout {
    fn declaration() -> Declaration {
        Declaration::new("lookout").uses::<PanTilt>().template(
            r#"<mujoco>
                 <worldbody>
                   <light pos="0 0 2" dir="0 0 -1"/>
                   <geom name="floor" type="plane" size="2 2 0.1" rgba="0.8 0.8 0.8 1"/>
                   <geom name="post" type="cylinder" size="0.02 0.075" pos="0 0 0.075"/>
                   <pan_tilt name="mount" pos="0 0 0.15"/>
                   <geom name="red_block" type="box" size="0.04 0.04 0.04" pos="0.8 0.2 0.04"
                         rgba="0.9 0.1 0.1 1"/>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

/// Where the red pixels of `image` are, as `(x, y)` offsets from its centre (pixels, x to the
/// right, y down); `None` when there are none.
pub fn red_offset(image: &yarok::mjc::image::RgbImage) -> Option<(f64, f64)> {
    let (mut sum_x, mut sum_y, mut count) = (0.0, 0.0, 0.0);
    for (x, y, pixel) in image.enumerate_pixels() {
        let [r, g, b] = pixel.0;
        if r > 120 && g < 60 && b < 60 {
            sum_x += f64::from(x);
            sum_y += f64::from(y);
            count += 1.0;
        }
    }
    (count > 0.0).then(|| {
        (
            sum_x / count - f64::from(image.width()) / 2.0 + 0.5,
            sum_y / count - f64::from(image.height()) / 2.0 + 0.5,
        )
    })
}

/// Turns the lookout's mount until the red block is at the centre of its camera's image (within
/// 1.5 pixels), each step by the angle the block's offset spans (the camera's 45° field over
/// its 72 rows), then 0.3 s for the servos to settle; the offset left.
pub async fn centre_on_red(pl: Pl) -> Result<(f64, f64), BoxError> {
    let mount: PanTilt = pl.get("/mount")?;
    let radians_per_pixel = 45f64.to_radians() / 72.0;
    let (mut pan, mut tilt) = mount.angles();
    for _ in 0..20 {
        let image = mount.eye().read()?;
        let (dx, dy) = red_offset(&image).ok_or("the camera sees no red")?;
        if dx.abs() < 1.5 && dy.abs() < 1.5 {
            return Ok((dx, dy));
        }
        pan -= dx * radians_per_pixel;
        tilt += dy * radians_per_pixel;
        mount.point(pan, tilt);
        // The servos settle in well under this; the next image measures what is left.
        pl.wait_seconds(0.3).await?;
    }
    Err("the block is not centred after 20 steps".into())
}
