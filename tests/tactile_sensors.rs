//! The DIGIT in the world: an imprint appears where an object presses into the gel, the untouched
//! gel without contact, a deeper press makes a larger imprint, two runs give the same bytes, and
//! on the gripper's pads both sensors feel a grasped block. The GelSight 2014 shows its imprint
//! where pressed too.

use yarok::components::tactile_sensors::{Contact, Digit, TactileSensor};
use yarok::components::worlds::EmptyWorld;
use yarok::prelude::*;
use yarok_test::assert_says;

/// A DIGIT facing up with its gel's face at z = 0.118 m, and a 5 mm sphere pressed `press`
/// metres into the gel at (`dx`, `dy`) from its centre (it stands still and collides with
/// nothing: only the camera sees it). The DIGIT draws with the reference Phong model unless
/// `calibration` says otherwise.
struct PressWorld;

impl Component for PressWorld {
    fn declaration() -> Declaration {
        Declaration::new("press_world")
            .extends::<EmptyWorld>()
            .uses::<Digit>()
            .default("press", 0.001)
            .default("dx", 0.003)
            .default("dy", -0.002)
            .default("noise", false)
            .default("calibration", "none")
            .template(
                r#"<mujoco><worldbody>
                  <digit name="digit" pos="{[0, 0, 0.1]}" noise="{noise}" calibration="{calibration}"/>
                  <geom name="indenter" type="sphere" size="0.005" pos="{dx} {dy} {0.118 + 0.005 - press}"
                        rgba="0.8 0.2 0.2 1"/>
                </worldbody></mujoco>"#,
            )
    }
}

/// The first frame of world `W` set up as `settings` say, and what the sensor `S` at `path`
/// feels then.
fn first_frame<W, S>(path: &'static str, settings: &[&str]) -> (image::RgbImage, Contact)
where
    W: Component,
    S: Clone + std::ops::Deref<Target = TactileSensor> + 'static,
{
    let out = std::rc::Rc::new(std::cell::RefCell::new(None));
    let result = std::rc::Rc::clone(&out);
    let mut builder = yarok::platform().world::<W>();
    for setting in settings {
        builder = builder.set(setting).unwrap();
    }
    builder
        .behaviour(move |pl| async move {
            let sensor: S = pl.get(path)?;
            pl.tick().await?;
            *result.borrow_mut() = Some((sensor.read(), sensor.contact()?));
            Ok(())
        })
        .run()
        .unwrap();
    let taken = out.borrow_mut().take();
    taken.unwrap()
}

/// The first frame of the DIGIT in [`PressWorld`] set up as `settings` say.
fn press(settings: &[&str]) -> (image::RgbImage, Contact) {
    first_frame::<PressWorld, Digit>("/digit", settings)
}

/// Pixels that differ from the untouched frame: their count and centroid (column, row).
fn imprint(frame: &image::RgbImage, untouched: &image::RgbImage) -> (usize, f64, f64) {
    let (mut count, mut sx, mut sy) = (0usize, 0.0, 0.0);
    for (x, y, pixel) in frame.enumerate_pixels() {
        let base = untouched.get_pixel(x, y);
        let diff = pixel
            .0
            .iter()
            .zip(base.0)
            .map(|(a, b)| a.abs_diff(b))
            .max()
            .unwrap_or(0);
        if diff > 8 {
            count += 1;
            sx += f64::from(x);
            sy += f64::from(y);
        }
    }
    (count, sx / count.max(1) as f64, sy / count.max(1) as f64)
}

#[test]
fn an_imprint_appears_where_the_object_presses() {
    imprint_where_pressed(&[], 4.0);
}

/// The calibrated model's imprint is lit from its sides as a real DIGIT's is, so where its
/// colour changes most lies a few pixels off the press.
#[test]
fn with_the_bundled_calibration_an_imprint_appears_where_the_object_presses() {
    imprint_where_pressed(&["calibration=\"bundled\""], 6.0);
}

/// The imprint's changed pixels centre within `tolerance` pixels of the press.
fn imprint_where_pressed(settings: &[&str], tolerance: f64) {
    let (untouched, nothing) = press(&[settings, &["press=-0.01"]].concat());
    assert!(!nothing.in_contact, "{nothing:?}");
    let (frame, contact) = press(settings);
    assert!(
        contact.in_contact && (contact.max_indentation - 0.001).abs() < 2e-4,
        "{contact:?}"
    );
    let (count, column, row) = imprint(&frame, &untouched);
    assert!(count > 50, "only {count} pixels changed");
    // 54.3 µm a pixel: 3 mm right of the centre, 2 mm towards the top.
    let (expected_column, expected_row) = (
        120.0 + 0.003 / 5.4347826087e-5,
        160.0 - 0.002 / 5.4347826087e-5,
    );
    assert!(
        (column - expected_column).abs() < tolerance && (row - expected_row).abs() < tolerance,
        "imprint at ({column:.1}, {row:.1}), expected ({expected_column:.1}, {expected_row:.1})"
    );
}

/// Without contact the frame is the optical model's image of the untouched gel, whatever lies
/// beyond it.
#[test]
fn without_contact_the_frame_is_the_untouched_gel() {
    use yarok::components::tactile::default_background;
    use yarok::components::tactile::phong::{PhongModel, PhongParams};
    let (far, contact) = press(&["press=-0.01"]);
    let (farther, _) = press(&["press=-0.05", "dx=0.0"]);
    assert!(!contact.in_contact);
    let mut model = PhongModel::new(PhongParams {
        texture_sigma: 0.0,
        elastomer_thickness: 0.002,
        min_depth: 0.018 - 0.002,
        ..PhongParams::digit_metric()
    });
    let untouched = model
        .render(&[0.018; 240 * 320], 240, &default_background(240, 320))
        .unwrap();
    assert!(
        far.as_raw() == &untouched,
        "the frame is not the untouched gel"
    );
    assert!(far == farther);
}

/// With the bundled calibration the untouched frame is the calibration's untouched gel (the
/// real DIGIT's, estimated from its frames), and a deeper press makes a larger imprint.
#[test]
fn with_the_bundled_calibration_the_untouched_gel_is_the_real_digits() {
    use yarok::components::tactile::calibration::Calibration;
    let (far, _) = press(&["calibration=\"bundled\"", "press=-0.01"]);
    assert!(far == *Calibration::digit().background());
    let (shallow, _) = press(&["calibration=\"bundled\"", "press=0.0005"]);
    let (deep, _) = press(&["calibration=\"bundled\"", "press=0.0015"]);
    let (shallow_pixels, _, _) = imprint(&shallow, &far);
    let (deep_pixels, _, _) = imprint(&deep, &far);
    assert!(
        deep_pixels > shallow_pixels && shallow_pixels > 50,
        "{shallow_pixels} then {deep_pixels} pixels"
    );
}

#[test]
fn a_deeper_press_makes_a_larger_imprint() {
    let (untouched, _) = press(&["press=-0.01"]);
    let (shallow, light) = press(&["press=0.0005"]);
    let (deep, firm) = press(&["press=0.0015"]);
    assert!(firm.area > light.area * 1.5, "{light:?} then {firm:?}");
    let (shallow_pixels, _, _) = imprint(&shallow, &untouched);
    let (deep_pixels, _, _) = imprint(&deep, &untouched);
    assert!(
        deep_pixels > shallow_pixels,
        "{shallow_pixels} then {deep_pixels} pixels"
    );
}

#[test]
fn two_runs_give_the_same_bytes() {
    let (first, _) = press(&["noise=true"]);
    let (second, _) = press(&["noise=true"]);
    assert!(first == second);
    let (quiet, _) = press(&[]);
    assert!(first != quiet, "the texture noise changes nothing");
}

/// In DigitWorld a DIGIT on each pad of the closing gripper feels the block, one from each
/// side, and neither feels anything before the gripper closes.
#[test]
fn a_sensor_on_each_finger_feels_the_block_from_its_side() {
    use std::f64::consts::PI;

    use yarok::components::grippers::Robotiq2f85;
    use yarok::components::robots::ur::{Ur5e, pose_from_vector};
    use yarok::components::toys::Block;
    use yarok::components::worlds::DigitWorld;

    yarok::platform()
        .world::<DigitWorld>()
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
            let left: Digit = pl.get("/arm/gripper/left_digit")?;
            let right: Digit = pl.get("/arm/gripper/right_digit")?;
            let block: Block = pl.get("/small")?;
            let down = |[x, y, _]: [f64; 3], z: f64| pose_from_vector([x, y, z, PI, 0.0, 0.0]);
            gripper.open().await?;
            arm.move_j_pose(down(block.position(), 0.12)).await?;
            arm.move_l(down(block.position(), 0.026)).await?;
            assert!(!left.contact()?.in_contact && !right.contact()?.in_contact);
            assert!(gripper.close().force(200).await?.object_detected);
            pl.wait_seconds(0.05).await?;
            for (side, digit) in [("left", &left), ("right", &right)] {
                let contact = digit.contact()?;
                assert!(
                    contact.in_contact && contact.area > 1e-6,
                    "{side}: {contact:?}"
                );
            }
            Ok(())
        })
        .run()
        .unwrap();
}

/// A GelSight 2014 fingertip facing up (gel face at z = 0.134 m) with a 5 mm sphere pressed 1 mm
/// into it at (5 mm, 3 mm) from its centre.
struct GelSightWorld;

impl Component for GelSightWorld {
    fn declaration() -> Declaration {
        Declaration::new("gelsight_world")
            .extends::<EmptyWorld>()
            .uses::<yarok::components::tactile_sensors::GelSight2014>()
            .default("press", 0.001)
            .template(
                r#"<mujoco><worldbody>
                  <gelsight2014 name="sensor" pos="{[0, 0, 0.1]}" noise="false"/>
                  <geom type="sphere" size="0.005" pos="0.005 0.003 {0.134 + 0.005 - press}"/>
                </worldbody></mujoco>"#,
            )
    }
}

#[test]
fn a_gelsight_shows_the_imprint_where_the_object_presses() {
    use yarok::components::tactile_sensors::GelSight2014;
    let run = |settings| first_frame::<GelSightWorld, GelSight2014>("/sensor", settings);
    let ((untouched, free), (pressed, contact)) = (run(&["press=-0.01"]), run(&["press=0.001"]));
    let (untouched, pressed) = (&untouched, &pressed);
    assert!(
        !free.in_contact && contact.in_contact,
        "{free:?} {contact:?}"
    );
    assert_eq!(pressed.dimensions(), (640, 480));
    let (count, column, row) = imprint(pressed, untouched);
    // 54.3 µm a pixel at the gel's face, 34 mm from the camera; the contact is 1 mm nearer.
    let scale = 34.0 / 33.0 / 5.4347826087e-5;
    let (expected_column, expected_row) = (320.0 + 0.005 * scale, 240.0 + 0.003 * scale);
    assert!(count > 100, "only {count} pixels changed");
    assert!(
        (column - expected_column).abs() < 6.0 && (row - expected_row).abs() < 6.0,
        "imprint at ({column:.1}, {row:.1}), expected ({expected_column:.1}, {expected_row:.1})"
    );
}

/// A sphere on a vertical slide, weightless, that a behaviour puts at a height.
#[derive(Clone, Debug)]
struct Indenter(yarok::mjc::Joint);

impl Component for Indenter {
    fn declaration() -> Declaration {
        Declaration::new("indenter").template(
            r#"<mujoco><worldbody>
              <body name="indenter" pos="0 0 0.15" gravcomp="1">
                <joint name="height" type="slide" axis="0 0 1"/>
                <geom type="sphere" size="0.005" mass="0.01"/>
              </body>
            </worldbody></mujoco>"#,
        )
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>();
    }
}

impl Interface<Sim> for Indenter {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        Ok(Indenter(bind.joint("height")?))
    }
}

/// A DIGIT at 100 frames/s (one every five 2 ms ticks) under the indenter, which passes through
/// its gel.
struct RateWorld;

impl Component for RateWorld {
    fn declaration() -> Declaration {
        Declaration::new("rate_world")
            .extends::<EmptyWorld>()
            .uses::<Digit>()
            .uses::<Indenter>()
            .template(
                r#"<mujoco><worldbody>
                  <digit name="digit" pos="{[0, 0, 0.1]}" fps="100" noise="false"/>
                  <indenter name="indenter"/>
                </worldbody>
                <!-- Placed by hand, not pushed: it passes through the gel, which sees it. -->
                <contact><exclude body1="indenter/indenter" body2="digit/sensor"/></contact>
                </mujoco>"#,
            )
    }
}

/// Frames come at the sensor's rate: a press shows in the first frame due after it, not
/// before, and every tick that was due a frame has made it.
#[test]
fn frames_come_at_the_sensor_rate_and_are_never_stale() {
    yarok::platform()
        .world::<RateWorld>()
        .behaviour(|pl| async move {
            let digit: Digit = pl.get("/digit")?;
            let indenter: Indenter = pl.get("/indenter")?;
            assert!((pl.timestep() - 0.002).abs() < 1e-12);
            // Frames at ticks 0, 5, 10, …: press right after the one of tick 5.
            pl.wait(|| pl.ticks() >= 5).await?;
            // The sphere's bottom 1 mm into the gel (its centre starts 0.15 m up).
            indenter.0.set_position(0.118 + 0.005 - 0.001 - 0.15);
            for tick in 6..=9 {
                pl.tick().await?;
                assert_eq!(pl.ticks(), tick);
                assert!(
                    !digit.contact()?.in_contact,
                    "a frame at tick {tick}, not due"
                );
            }
            pl.tick().await?;
            assert!(
                digit.contact()?.in_contact,
                "the frame due at tick 10 is missing"
            );
            // Lifted again: the frame due at tick 15 shows it.
            indenter.0.set_position(0.0);
            pl.wait(|| pl.ticks() >= 14).await?;
            assert!(digit.contact()?.in_contact);
            pl.tick().await?;
            assert!(
                !digit.contact()?.in_contact,
                "the frame due at tick 15 is stale"
            );
            Ok(())
        })
        .run()
        .unwrap();
}

/// A GelTip pointing up (its base at z = 0.1 m, its tip at 0.145 m) and a 5 mm sphere pressed
/// 1 mm into it at `at` (`tip` or `side`: 20 mm up its tube, on +x).
struct GelTipWorld;

impl Component for GelTipWorld {
    fn declaration() -> Declaration {
        Declaration::new("geltip_press_world")
            .extends::<EmptyWorld>()
            .uses::<yarok::components::tactile_sensors::GelTip>()
            .default("press", 0.001)
            .default("side", false)
            .template(
                r#"<mujoco><worldbody>
                  <geltip name="sensor" pos="{[0, 0, 0.1]}"/>
                  <geom type="sphere" size="0.005"
                        pos="{[0.015 + 0.005 - press, 0, 0.12] if side else [0, 0, 0.145 + 0.005 - press]}"/>
                </worldbody></mujoco>"#,
            )
    }
}

#[test]
fn a_geltip_shows_presses_on_its_tip_and_on_its_side_where_they_are() {
    use yarok::components::tactile_sensors::GelTip;
    let run = |settings| first_frame::<GelTipWorld, GelTip>("/sensor", settings);
    let (untouched, free) = run(&["press=-0.01"]);
    assert!(!free.in_contact, "{free:?}");
    assert_eq!(untouched.dimensions(), (320, 240));
    let f = 240.0 / (2.0 * 35f64.to_radians().tan());
    for (settings, expected) in [
        (&["press=0.001"][..], (159.5, 119.5)),
        (
            &["press=0.001", "side=true"][..],
            (159.5 + f * 0.014 / 0.02, 119.5),
        ),
    ] {
        let (frame, contact) = run(settings);
        assert!(
            contact.in_contact && contact.max_indentation > 5e-4,
            "{settings:?}: {contact:?}"
        );
        let (count, column, row) = imprint(&frame, &untouched);
        assert!(count > 20, "{settings:?}: only {count} pixels changed");
        // On the tube the surface slants away from the camera, and the imprint's shading
        // with it: its centroid sits up to 1 mm (10 px) towards the image's centre.
        assert!(
            (column - expected.0).abs() < 12.0 && (row - expected.1).abs() < 6.0,
            "{settings:?}: imprint at ({column:.1}, {row:.1}), expected {expected:?}"
        );
    }
}

/// A probe a plugin read: its component, name, image size, and whether it showed the latest
/// frame.
type ProbeSeen = (String, String, (u32, u32), bool);

/// Lists the probes it sees and reads each one after the first tick.
#[derive(Default)]
struct ProbeReader {
    seen: std::rc::Rc<std::cell::RefCell<Vec<ProbeSeen>>>,
}

impl yarok::Plugin for ProbeReader {
    fn step(&mut self, world: &yarok::World<'_>) -> Result<(), yarok::BoxError> {
        if world.pl().ticks() == 1 {
            let digit: Digit = world.pl().get("/digit")?;
            for probe in world.probes() {
                let image = probe.read()?;
                let current = match &image {
                    yarok::core::component::ProbeImage::Rgb { pixels, .. } => {
                        *pixels == digit.read().into_raw()
                    }
                    yarok::core::component::ProbeImage::Depth { metres, .. } => {
                        *metres == digit.read_depth()?.into_raw()
                    }
                    _ => false,
                };
                self.seen.borrow_mut().push((
                    probe.component().to_owned(),
                    probe.name().to_owned(),
                    image.size(),
                    current,
                ));
            }
        }
        Ok(())
    }
}

#[test]
fn plugins_see_the_sensors_probes() {
    let reader = ProbeReader::default();
    let seen = std::rc::Rc::clone(&reader.seen);
    yarok::platform()
        .world::<PressWorld>()
        .plugin(reader)
        .behaviour(|pl| async move { pl.wait(|| pl.ticks() >= 2).await.map_err(Into::into) })
        .run()
        .unwrap();
    assert_eq!(
        *seen.borrow(),
        [
            ("/digit".to_owned(), "image".to_owned(), (240, 320), true),
            ("/digit".to_owned(), "depth".to_owned(), (240, 320), true),
        ]
    );
}

#[test]
fn the_gel_geometry_of_the_optical_model_cannot_be_changed() {
    let error = yarok::platform()
        .world::<PressWorld>()
        .set("/digit/gel_face=0.02")
        .unwrap()
        .behaviour(|_| async { Ok(()) })
        .run()
        .unwrap_err()
        .to_string();
    assert_says(&error, &["/digit", "gel_face", "0.018"]);
    // The housing is the sensor's own and may change.
    let (_, contact) =
        first_frame::<PressWorld, Digit>("/digit", &["/digit/housing=[0.015, 0.012]"]);
    assert!(contact.in_contact);
}
