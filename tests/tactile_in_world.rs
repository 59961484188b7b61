//! Tactile sensors feel what really touches them in the world: in `DigitWorld` each DIGIT's
//! imprint is the grasped block's face where MuJoCo's contacts put it (not the gripper's marker
//! sphere), the block stays outside the gels, and nothing is felt without it; in `GelTipWorld`
//! the GelTips feel the rope where it touches them; on the tactile rig a ball pressed with two
//! forces sinks as deep as the DIGIT's elastomer law says.

use std::f64::consts::PI;

use yarok::components::grippers::Robotiq2f85;
use yarok::components::robots::ur::{Ur5e, pose_from_vector};
use yarok::components::tactile::elastomer::Elastomer;
use yarok::components::tactile_sensors::{Digit, GelContact, GelTip, TactileSensor};
use yarok::components::toys::{Block, Rope, Spot};
use yarok::components::worlds::{DigitWorld, GelTipWorld, TactileRigWorld};

/// A DIGIT's image: 240 × 320, 54.35 µm a pixel at its gel's face, 18 mm from its camera.
const DIGIT_PIXEL: f64 = 5.4347826087e-5;
const DIGIT_FACE: f64 = 0.018;

/// Indentation (metres) above which a pixel counts as pressed.
const PRESSED: f32 = 2e-5;

/// The pressed pixels of a sensor's latest depth: (column, row) each.
fn patch(sensor: &TactileSensor, surface: impl Fn(u32, u32) -> f32) -> Vec<(u32, u32)> {
    let depth = sensor.read_depth().unwrap();
    depth
        .enumerate_pixels()
        .filter(|(x, y, depth)| surface(*x, *y) - depth[0] > PRESSED)
        .map(|(x, y, _)| (x, y))
        .collect()
}

/// Bounds (min x, max x, min y, max y) of points.
fn bounds(points: impl Iterator<Item = [f64; 2]>) -> [f64; 4] {
    points.fold(
        [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ],
        |[x0, x1, y0, y1], [x, y]| [x0.min(x), x1.max(x), y0.min(y), y1.max(y)],
    )
}

/// In DigitWorld, grasps the small block (or closes where it would be, `with_block` false) and
/// checks both DIGITs.
fn grasp_in_digit_world(with_block: bool) {
    yarok::platform()
        .world::<DigitWorld>()
        .set(&format!("blocks={}", if with_block { "true" } else { "false" }))
        .unwrap()
        .behaviour(move |pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
            let sensors: [Digit; 2] = [
                pl.get("/arm/gripper/left_digit")?,
                pl.get("/arm/gripper/right_digit")?,
            ];
            let at = if with_block {
                pl.get::<Block>("/small")?.position()
            } else {
                [0.45, 0.12, 0.415]
            };
            let down = |[x, y, _]: [f64; 3], z: f64| pose_from_vector([x, y, z, PI, 0.0, 0.0]);
            gripper.open().await?;
            arm.move_j_pose(down(at, 0.12)).await?;
            arm.move_l(down(at, 0.026)).await?;
            if with_block {
                gripper.close().force(200).await?;
            } else {
                // As far as the block held the fingers apart: the gripper's marker sphere
                // between the gels, and nothing else.
                gripper.move_to(75).await?;
            }
            pl.wait_seconds(0.1).await?;
            for (side, sensor) in ["left", "right"].into_iter().zip(&sensors) {
                let pressed = patch(sensor, |_, _| DIGIT_FACE as f32);
                let contacts = sensor.gel_contacts()?;
                let felt = sensor.contact()?;
                if !with_block {
                    assert!(
                        pressed.is_empty() && contacts.is_empty() && !felt.in_contact,
                        "{side}: {} pixels pressed with no block (the marker sphere?), {contacts:?}",
                        pressed.len()
                    );
                    continue;
                }
                check_block_face(side, &pressed, &contacts);
                let law = Elastomer::DIGIT.indentation(felt.force);
                assert!(
                    felt.force > 5.0 && (felt.max_indentation - law).abs() < 5e-6,
                    "{side}: {felt:?}, the law says {law} m"
                );
            }
            if with_block {
                let [left, right] = sensors.each_ref().map(|s| s.gel_contacts().unwrap());
                let gap = |contacts: &[GelContact]| {
                    contacts.iter().map(|c| c.position[2]).fold(f64::INFINITY, f64::min)
                };
                // The block sits on both gels' faces, not inside them.
                for (side, contacts) in [("left", &left), ("right", &right)] {
                    assert!(
                        gap(contacts) > DIGIT_FACE - 3e-4,
                        "{side}: the block is {:.2} mm into the gel",
                        (DIGIT_FACE - gap(contacts)) * 1e3
                    );
                }
            }
            Ok(())
        })
        .run()
        .unwrap();
}

/// The pressed patch is where MuJoCo's gel–block contacts are: their extent (clipped to the
/// camera's field) and the patch's agree within 1.5 mm on every side, and it is a face (over
/// 100 mm²), not a 3 mm sphere.
fn check_block_face(side: &str, pressed: &[(u32, u32)], contacts: &[GelContact]) {
    assert!(
        !contacts.is_empty(),
        "{side}: no contact between the gel and the block"
    );
    let metres = |(x, y): (u32, u32)| {
        [
            (f64::from(x) + 0.5 - 120.0) * DIGIT_PIXEL,
            (f64::from(y) + 0.5 - 160.0) * DIGIT_PIXEL,
        ]
    };
    let area = pressed.len() as f64 * DIGIT_PIXEL * DIGIT_PIXEL;
    assert!(area > 100e-6, "{side}: only {:.1} mm² pressed", area * 1e6);
    let seen = bounds(pressed.iter().map(|&p| metres(p)));
    let field = [120.0 * DIGIT_PIXEL, 160.0 * DIGIT_PIXEL];
    let touched = bounds(contacts.iter().map(|c| {
        let scale = DIGIT_FACE / c.position[2];
        [
            (c.position[0] * scale).clamp(-field[0], field[0]),
            (c.position[1] * scale).clamp(-field[1], field[1]),
        ]
    }));
    for (edge, (seen, touched)) in ["left", "right", "top", "bottom"]
        .iter()
        .zip(seen.iter().zip(touched))
    {
        assert!(
            (seen - touched).abs() < 1.5e-3,
            "{side} DIGIT, {edge} edge: the imprint ends at {:.2} mm, the contacts at {:.2} mm \
             (imprint {seen:?}, contacts {touched:?})",
            seen * 1e3,
            touched * 1e3
        );
    }
}

#[test]
fn in_digit_world_each_digit_feels_the_grasped_blocks_face() {
    grasp_in_digit_world(true);
}

#[test]
fn in_digit_world_without_the_block_the_digits_feel_nothing() {
    grasp_in_digit_world(false);
}

/// In GelTipWorld, with the rope's end pinched, every contact between a GelTip and the rope
/// shows in that GelTip's depth where its camera sees the contact, and the rope does not pass
/// into the membrane.
#[test]
fn in_geltip_world_the_geltips_feel_the_rope_where_it_touches() {
    yarok::platform()
        .world::<GelTipWorld>()
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
            let sensors: [GelTip; 2] = [
                pl.get("/arm/gripper/left_geltip")?,
                pl.get("/arm/gripper/right_geltip")?,
            ];
            let rope: Rope = pl.get("/rope")?;
            let [[x, y, z], _] = rope.ends();
            let table = pl.get::<Spot>("/target")?.position()[2];
            let down = |z: f64| pose_from_vector([x, y, z, PI, 0.0, 0.0]);
            gripper.open().await?;
            let untouched = sensors
                .each_ref()
                .map(|s| s.read_depth().unwrap().into_raw());
            let above = arm
                .kinematics()
                .solutions(&down(0.12), &arm.q())
                .into_iter()
                .find(|q| q[1] < 0.0 && q[1] > -PI && q[2] > 0.0)
                .ok_or("out of reach")?;
            arm.move_j(above).await?;
            // The tubes (not their domes) at the rope's end, where it rests on the peg.
            arm.move_l(down(z - table + 0.005)).await?;
            gripper.close().force(60).await?;
            pl.wait_seconds(0.1).await?;
            // The GelTip's camera: 320 × 240, 70° vertical field, at the sensor's origin
            // looking along +z (image right = +x, down = +y).
            let focal = 120.0 / (35f64.to_radians()).tan();
            for ((side, sensor), untouched) in
                ["left", "right"].into_iter().zip(&sensors).zip(&untouched)
            {
                let depth = sensor.read_depth()?;
                let contacts = sensor.gel_contacts()?;
                assert!(
                    !contacts.is_empty(),
                    "{side}: the rope does not touch the GelTip"
                );
                let mut seen = 0;
                for contact in &contacts {
                    let [cx, cy, cz] = contact.position;
                    let (u, v) = (159.5 + focal * cx / cz, 119.5 + focal * cy / cz);
                    if !(3.0..316.0).contains(&u) || !(3.0..236.0).contains(&v) {
                        continue;
                    }
                    seen += 1;
                    let pressed = (-3..=3)
                        .flat_map(|dv| (-3..=3).map(move |du| (du, dv)))
                        .any(|(du, dv)| {
                            let (px, py) = ((u as i32 + du) as u32, (v as i32 + dv) as u32);
                            untouched[(py * 320 + px) as usize] - depth.get_pixel(px, py)[0]
                                > PRESSED
                        });
                    assert!(
                        pressed,
                        "{side}: the contact at {:?} mm (pixel {u:.0}, {v:.0}) is not in the depth",
                        contact.position.map(|m| (m * 1e4).round() / 10.0)
                    );
                    // MuJoCo's soft contact lets a 10 g segment pinched this hard sink about
                    // 0.5 mm (the contact's midpoint); a rope passing through would be ~6 mm in.
                    let radius = cx.hypot(cy);
                    assert!(
                        radius > 0.015 - 7.5e-4 || cz > 0.045 - 0.015,
                        "{side}: the rope is {:.2} mm into the tube",
                        (0.015 - radius) * 1e3
                    );
                }
                assert!(seen > 0, "{side}: the camera sees none of {contacts:?}");
                assert!(sensor.contact()?.in_contact);
            }
            Ok(())
        })
        .run()
        .unwrap();
}

/// On the tactile rig, pressing by force: a 4 mm ball on a DIGIT pressed with two forces sinks
/// as deep as the DIGIT's elastomer law says for the force MuJoCo measures, near the force asked.
#[test]
fn on_the_rig_a_ball_pressed_with_two_forces_sinks_as_the_law_says() {
    yarok::platform()
        .world::<TactileRigWorld>()
        .set("sensor=\"digit\"")
        .unwrap()
        .set("pressing=\"force\"")
        .unwrap()
        .behaviour(|pl| async move {
            let rig: TactileRigWorld = pl.get("/")?;
            let mut depths = Vec::new();
            for force in [2.0, 12.0] {
                let sample = rig.press_with_force([0.001, -0.002], force).await?;
                let felt = sample.contact;
                let law = Elastomer::DIGIT.indentation(felt.force);
                assert!(
                    (felt.force - force).abs() < 0.15 * force,
                    "asked {force} N, MuJoCo measures {} N",
                    felt.force
                );
                assert!(
                    (felt.max_indentation - law).abs() < 5e-6,
                    "{force} N: {} m deep, the law says {law} m",
                    felt.max_indentation
                );
                depths.push(felt.max_indentation);
            }
            assert!(depths[1] > depths[0] * 1.5, "{depths:?}");
            Ok(())
        })
        .run()
        .unwrap();
}
