//! `parent=` places a child at a body or at a site; at a site, the child takes the site's
//! position and orientation, as MuJoCo's attach does.

use std::sync::Arc;

use yarok_core::component::{Component, Declaration};
use yarok_core::compose::compose;
use yarok_mjc::{Data, Model};

struct Wrist;
impl Component for Wrist {
    fn declaration() -> Declaration {
        Declaration::new("wrist").template(
            r#"<mujoco>
                 <compiler angle="radian"/>
                 <worldbody>
                   <body name="forearm" pos="0.1 0.2 0.5" euler="0.3 0 0.2">
                     <geom size="0.02"/>
                     <site name="flange" pos="0 0.05 0.1" euler="0.4 -0.7 1.1"/>
                   </body>
                   <site name="base" pos="1 0 0" quat="0 0 0 1"/>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

struct Cell;
impl Component for Cell {
    fn declaration() -> Declaration {
        Declaration::new("cell").uses::<Wrist>().template(
            r#"<mujoco>
                 <compiler angle="radian"/>
                 <worldbody>
                   <wrist name="w">
                     <body name="tool" parent="flange"><geom size="0.01"/></body>
                     <body name="pedestal" parent="base"><geom size="0.01"/></body>
                     <body name="bracelet" parent="forearm"><geom size="0.01"/></body>
                   </wrist>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
}

/// Same rotation: q and -q are the same orientation.
fn same_rotation(a: [f64; 4], b: [f64; 4]) -> bool {
    let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    (dot.abs() - 1.0).abs() < 1e-9
}

#[test]
fn a_child_mounted_at_a_site_takes_the_sites_pose() {
    let composition = compose::<Cell>().unwrap();
    let model = Arc::new(Model::from_composition(&composition).unwrap());
    let mut data = Data::new(&model).unwrap();
    data.forward();
    for (body, site) in [("tool", "w/flange"), ("pedestal", "w/base")] {
        let body = data.body_pose(model.body(body).unwrap());
        let site = data.site_pose(model.site(site).unwrap());
        assert!(close(body.pos, site.pos), "{body:?} vs {site:?}");
        assert!(same_rotation(body.quat, site.quat), "{body:?} vs {site:?}");
    }
    let bracelet = data.body_pose(model.body("bracelet").unwrap());
    let forearm = data.body_pose(model.body("w/forearm").unwrap());
    assert!(close(bracelet.pos, forearm.pos));
    assert!(same_rotation(bracelet.quat, forearm.quat));
}
