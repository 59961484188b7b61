//! Measures, side by side in one run, composing a world the size of the original's DigitUR5World
//! (a floor world, a six-joint arm with meshes, a two-finger gripper with a tendon and
//! equalities, two tactile sensors with cameras and lights, props) against parsing the composed
//! MJCF back and against MuJoCo compiling it. Target: compose ≤ 1 ms (the Python original takes
//! about 9 ms for its template build of that world).
//!
//! ```text
//! cargo bench --bench compose
//! ```

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Duration;

use yarok::core::component::{Component, Declaration};
use yarok::core::compose::compose;
use yarok::core::template::xml::Element;
use yarok::mjc::Model;

mod measure;
use measure::mean_times;

static MESHES: OnceLock<PathBuf> = OnceLock::new();

/// A folder of small meshes standing for the arm's, gripper's and sensors' mesh files.
fn meshes() -> &'static Path {
    MESHES.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("yarok-compose-bench-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let tetra =
            "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
        for name in [
            "base", "shoulder", "upperarm", "forearm", "wrist1", "wrist2", "wrist3", "palm",
            "finger", "pad", "gel", "shell",
        ] {
            std::fs::write(dir.join(format!("{name}.obj")), tetra).unwrap();
        }
        dir
    })
}

struct Floor;
impl Component for Floor {
    fn declaration() -> Declaration {
        Declaration::new("floor").template(
            r#"<mujoco>
                 <compiler angle="radian" autolimits="true"/>
                 <visual><map znear="0.001" zfar="100"/><global offwidth="640" offheight="480"/></visual>
                 <asset>
                   <texture name="grid" type="2d" builtin="checker" rgb1=".2 .3 .4" rgb2=".1 .15 .2" width="512" height="512" mark="cross" markrgb=".8 .8 .8"/>
                   <material name="grid" texture="grid" texrepeat="1 1" texuniform="true" reflectance=".3"/>
                 </asset>
                 <worldbody>
                   <light directional="true" diffuse="1 1 1" specular=".1 .1 .1" pos="0 0 5" dir="0 0 -1"/>
                   <body name="floor"><geom name="ground" type="plane" size="0 0 1" material="grid"/></body>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

struct Arm;
impl Component for Arm {
    fn declaration() -> Declaration {
        Declaration::new("arm").default("kp", 2000.0).asset_dir(meshes()).template(
            r#"<mujoco>
                 <compiler angle="radian"/>
                 <default>
                   <default class="arm">
                     <joint axis="0 1 0" range="-6.28 6.28" armature="0.1"/>
                     <position ctrlrange="-6.28 6.28" kp="{kp}"/>
                     <default class="visual"><geom type="mesh" contype="0" conaffinity="0" group="2"/></default>
                     <default class="collision"><geom type="capsule" group="3"/></default>
                   </default>
                 </default>
                 <asset>
                   <material name="metal" rgba="0.58 0.58 0.58 1"/>
                   <for each="['base', 'shoulder', 'upperarm', 'forearm', 'wrist1', 'wrist2', 'wrist3']" as="part">
                     <mesh name="{part}" file="{part}.obj"/>
                   </for>
                 </asset>
                 <worldbody>
                   <body name="base" childclass="arm">
                     <geom class="visual" mesh="base" material="metal"/>
                     <body name="shoulder_link" pos="0 0 0.163">
                       <joint name="shoulder_pan" axis="0 0 1"/>
                       <geom class="visual" mesh="shoulder" material="metal"/>
                       <geom class="collision" size="0.06 0.06" pos="0 0 -0.04"/>
                       <body name="upper_arm_link" pos="0 0.138 0" quat="1 0 1 0">
                         <joint name="shoulder_lift"/>
                         <geom class="visual" mesh="upperarm" material="metal"/>
                         <geom class="collision" size="0.05 0.2" pos="0 0 0.2"/>
                         <body name="forearm_link" pos="0 -0.131 0.425">
                           <joint name="elbow"/>
                           <geom class="visual" mesh="forearm" material="metal"/>
                           <geom class="collision" size="0.038 0.19" pos="0 0 0.2"/>
                           <body name="wrist_1_link" pos="0 0 0.392" quat="1 0 1 0">
                             <joint name="wrist_1"/>
                             <geom class="visual" mesh="wrist1" material="metal"/>
                             <body name="wrist_2_link" pos="0 0.127 0">
                               <joint name="wrist_2" axis="0 0 1"/>
                               <geom class="visual" mesh="wrist2" material="metal"/>
                               <body name="wrist_3_link" pos="0 0 0.1">
                                 <joint name="wrist_3"/>
                                 <geom class="visual" mesh="wrist3" material="metal"/>
                                 <site name="attachment_site" pos="0 0.1 0"/>
                                 <body name="ee_link" pos="0 0.1 0" quat="-1 1 0 0"/>
                               </body>
                             </body>
                           </body>
                         </body>
                       </body>
                     </body>
                   </body>
                 </worldbody>
                 <actuator>
                   <for each="['shoulder_pan', 'shoulder_lift', 'elbow', 'wrist_1', 'wrist_2', 'wrist_3']" as="j">
                     <position class="arm" name="{j}" joint="{j}"/>
                   </for>
                 </actuator>
                 <sensor>
                   <for each="['shoulder_pan', 'shoulder_lift', 'elbow', 'wrist_1', 'wrist_2', 'wrist_3']" as="j">
                     <jointpos name="{j}_pos" joint="{j}"/>
                   </for>
                   <framepos name="tool" objtype="site" objname="attachment_site"/>
                 </sensor>
                 <keyframe><key name="home" qpos="0 -1.57 1.57 -1.57 -1.57 0"/></keyframe>
               </mujoco>"#,
        )
    }
}

struct Gripper;
impl Component for Gripper {
    fn declaration() -> Declaration {
        Declaration::new("gripper").asset_dir(meshes()).template(
            r#"<mujoco>
                 <compiler angle="radian"/>
                 <default>
                   <default class="gripper">
                     <joint axis="1 0 0" damping="0.1" armature="0.001"/>
                     <geom type="mesh" group="2"/>
                     <default class="driver"><joint range="0 0.8"/></default>
                     <default class="follower"><joint range="-0.87 0.87"/></default>
                   </default>
                 </default>
                 <asset>
                   <for each="['palm', 'finger', 'pad']" as="part"><mesh name="{part}" file="{part}.obj"/></for>
                 </asset>
                 <worldbody>
                   <body name="base" childclass="gripper">
                     <geom mesh="palm"/>
                     <for each="[('right', 1), ('left', -1)]" as="side">
                       <body name="{side[0]}_driver" pos="0 {0.0306 * side[1]} 0.0548">
                         <joint name="{side[0]}_driver_joint" class="driver"/>
                         <geom mesh="finger"/>
                         <body name="{side[0]}_coupler" pos="0 0.0315 -0.0041">
                           <joint name="{side[0]}_coupler_joint" class="follower"/>
                           <geom mesh="finger"/>
                         </body>
                       </body>
                       <body name="{side[0]}_spring" pos="0 {0.0132 * side[1]} 0.0609">
                         <joint name="{side[0]}_spring_joint" class="follower"/>
                         <geom mesh="finger"/>
                         <body name="{side[0]}_follower" pos="0 0.055 0.0375">
                           <joint name="{side[0]}_follower_joint" class="follower"/>
                           <geom mesh="finger"/>
                           <body name="{side[0]}_pad" pos="0 -0.0189 0.01352">
                             <geom mesh="pad"/>
                             <body name="{side[0]}_tip" pos="0 0 0.02"/>
                           </body>
                         </body>
                       </body>
                     </for>
                   </body>
                 </worldbody>
                 <contact><exclude body1="base" body2="left_driver"/><exclude body1="base" body2="right_driver"/></contact>
                 <tendon>
                   <fixed name="split"><joint joint="right_driver_joint" coef="0.5"/><joint joint="left_driver_joint" coef="0.5"/></fixed>
                 </tendon>
                 <equality>
                   <connect anchor="0 0 0" body1="right_follower" body2="right_coupler" solimp="0.95 0.99 0.001"/>
                   <connect anchor="0 0 0" body1="left_follower" body2="left_coupler" solimp="0.95 0.99 0.001"/>
                   <joint joint1="right_driver_joint" joint2="left_driver_joint" polycoef="0 1 0 0 0"/>
                 </equality>
                 <actuator><general name="fingers" tendon="split" ctrlrange="0 255" gainprm="0.3137" biasprm="0 -100 -10"/></actuator>
               </mujoco>"#,
        )
    }
}

struct Tactile;
impl Component for Tactile {
    fn declaration() -> Declaration {
        Declaration::new("tactile").default("resolution", vec![320, 240]).asset_dir(meshes()).template(
            r#"<mujoco>
                 <compiler angle="radian"/>
                 <asset><mesh name="gel" file="gel.obj"/><mesh name="shell" file="shell.obj"/><material name="gel" rgba="0.9 0.9 0.9 1"/></asset>
                 <worldbody>
                   <body name="sensor">
                     <geom type="mesh" mesh="shell" rgba="0.1 0.1 0.1 1"/>
                     <geom name="gel" type="mesh" mesh="gel" material="gel"/>
                     <camera name="camera" pos="0 0 0.01" fovy="70" resolution="{resolution}"/>
                     <for each="[(1, 0, 0), (0, 1, 0), (0, 0, 1)]" as="colour">
                       <light name="led{colour[0]}{colour[1]}{colour[2]}" pos="0 0 0.005" diffuse="{colour}" castshadow="false" if="True"/>
                     </for>
                   </body>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

struct DigitWorld;
impl Component for DigitWorld {
    fn declaration() -> Declaration {
        Declaration::new("digit_world").extends::<Floor>().uses::<Arm>().uses::<Gripper>().uses::<Tactile>().template(
            r#"<mujoco>
                 <worldbody>
                   <body name="object" pos="0.5 0 0.1"><freejoint/><geom type="cylinder" size="0.02 0.11" mass="0.0001" euler="0 1.57 0"/></body>
                   <body name="holder" pos="0.5 0 0">
                     <for each="range(6)" as="i"><geom name="holder{i}" type="box" size="0.01 0.05 0.04" pos="{0.03 * i} 0 0.04"/></for>
                   </body>
                   <arm name="arm">
                     <gripper name="gripper" parent="ee_link">
                       <body name="digit1_mount" parent="left_tip" xyaxes="0 0 -1 1 0 0" pos="-0.001 0.009 0.064"><tactile name="digit1"/></body>
                       <body name="digit2_mount" parent="right_tip" xyaxes="0 0 -1 1 0 0" pos="-0.001 0.009 0.064"><tactile name="digit2"/></body>
                     </gripper>
                   </arm>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let composition = compose::<DigitWorld>()?;
    let xml = composition.to_xml();
    let model = Model::from_composition(&composition)?;
    println!(
        "world: {} components, {} elements, {} bodies in MuJoCo",
        composition.instances.len(),
        composition.mjcf.descendants().len(),
        model.count(yarok::mjc::ObjectKind::Body)
    );
    let [compose_time, parse_time, compile_time] = mean_times(|variant| match variant {
        0 => compose::<DigitWorld>().expect("compose").instances.len(),
        1 => Element::parse(&xml).expect("parse").children.len(),
        _ => Model::from_composition(&composition)
            .expect("compile")
            .count(yarok::mjc::ObjectKind::Body),
    });
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    println!("\n{:<34} {:>10}", "step", "ms");
    println!(
        "{:<34} {:>10.3}",
        "compose (templates → MJCF)",
        ms(compose_time)
    );
    println!("{:<34} {:>10.3}", "parse the composed MJCF", ms(parse_time));
    println!(
        "{:<34} {:>10.3}",
        "MuJoCo compile (2 passes: keys)",
        ms(compile_time)
    );
    println!(
        "\ncompose / parse   = {:.1}x",
        ms(compose_time) / ms(parse_time)
    );
    println!(
        "compose / compile = {:.3}x",
        ms(compose_time) / ms(compile_time)
    );
    println!("compose / 1 ms target = {:.2}", ms(compose_time));
    std::fs::remove_dir_all(meshes())?;
    Ok(())
}
