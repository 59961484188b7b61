//! Tactile sensors with `--env real` (feature `camera`): a DIGIT's frames are its camera's
//! landscape frames turned to the model's portrait (as digit-interface's `get_frame` turns
//! them; its VGA stream too), a GelTip's come as they are; both decode as ffmpeg decodes them; depth and contact
//! measures are errors saying a real sensor has none, and the gel's geometry is the model's.
#![cfg(feature = "camera")]

use std::path::Path;
use std::process::Command;

use yarok::components::tactile_sensors::{Digit, GelTip, TactileError};
use yarok::{Component, Declaration};
use yarok_test::assert_says;

/// A DIGIT and a GelTip side by side.
struct TwoSensors;

impl Component for TwoSensors {
    fn declaration() -> Declaration {
        Declaration::new("two_sensors")
            .uses::<Digit>()
            .uses::<GelTip>()
            .template(
                r#"<mujoco><worldbody>
                     <digit name="digit"/>
                     <geltip name="geltip" pos="0.1 0 0"/>
                   </worldbody></mujoco>"#,
            )
    }
}

/// Runs ffmpeg with `args`.
fn ffmpeg(args: &[&str]) {
    let status = Command::new("ffmpeg")
        .args(["-hide_banner", "-loglevel", "error", "-y"])
        .args(args)
        .status()
        .expect("ffmpeg runs (scripts/setup-test-peers.sh installs it)");
    assert!(status.success(), "ffmpeg {args:?}");
}

/// One frame of ffmpeg's test pattern, `width`×`height`, as an MJPEG stream in `folder`, and
/// ffmpeg's own RGB decode of it.
fn pattern(folder: &Path, width: u32, height: u32) -> (String, image::RgbImage) {
    let stream = folder.join(format!("pattern_{width}x{height}.mjpeg"));
    let raw = folder.join(format!("pattern_{width}x{height}.rgb"));
    let size = format!("testsrc=size={width}x{height}:rate=1");
    ffmpeg(&[
        "-f",
        "lavfi",
        "-i",
        &size,
        "-frames:v",
        "1",
        "-f",
        "mjpeg",
        stream.to_str().unwrap(),
    ]);
    ffmpeg(&[
        "-f",
        "mjpeg",
        "-i",
        stream.to_str().unwrap(),
        "-f",
        "rawvideo",
        "-pix_fmt",
        "rgb24",
        raw.to_str().unwrap(),
    ]);
    let rgb = image::RgbImage::from_raw(width, height, std::fs::read(raw).unwrap()).unwrap();
    (stream.to_str().unwrap().to_owned(), rgb)
}

fn mean_difference(ours: &image::RgbImage, theirs: &image::RgbImage) -> f64 {
    assert_eq!(ours.dimensions(), theirs.dimensions());
    let total: u64 = ours
        .as_raw()
        .iter()
        .zip(theirs.as_raw())
        .map(|(a, b)| u64::from(a.abs_diff(*b)))
        .sum();
    total as f64 / ours.as_raw().len() as f64
}

#[test]
fn real_sensors_show_their_cameras_frames_and_have_no_depth() {
    let folder = tempfile::tempdir().unwrap();
    // Both cameras are 320×240: the DIGIT's QVGA stream, the GelTip's own.
    let (stream, camera) = pattern(folder.path(), 320, 240);
    let portrait = image::imageops::rotate270(&camera);
    let upside_down = image::imageops::rotate90(&camera);
    yarok::platform()
        .world::<TwoSensors>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/digit/file=\"{stream}\""),
            "--set".to_owned(),
            format!("interfaces/geltip/file=\"{stream}\""),
        ])
        .unwrap()
        .behaviour(move |pl| async move {
            let digit: Digit = pl.get("/digit")?;
            let frame = digit.read();
            assert_eq!(frame.dimensions(), (240, 320), "portrait, as in sim");
            let turned = mean_difference(&frame, &portrait);
            assert!(turned <= 1.0, "{turned} levels from ffmpeg's, turned");
            assert!(mean_difference(&frame, &upside_down) > 20.0);
            assert!(matches!(digit.read_depth(), Err(TactileError::NoDepth)));
            assert!(matches!(digit.contact(), Err(TactileError::NoDepth)));
            assert_eq!(digit.surface_distance(0.0, 0.0), Some(0.018));

            let geltip: GelTip = pl.get("/geltip")?;
            let frame = geltip.read();
            let same = mean_difference(&frame, &camera);
            assert!(same <= 1.0, "{same} levels from ffmpeg's");
            assert!(geltip.contact().is_err());
            Ok(())
        })
        .run()
        .unwrap();
}

/// A DIGIT alone.
struct DigitOnly;

impl Component for DigitOnly {
    fn declaration() -> Declaration {
        Declaration::new("digit_only")
            .uses::<Digit>()
            .template(r#"<mujoco><worldbody><digit name="digit"/></worldbody></mujoco>"#)
    }
}

#[test]
fn a_digits_vga_stream_comes_turned_to_480_by_640() {
    let folder = tempfile::tempdir().unwrap();
    let (stream, camera) = pattern(folder.path(), 640, 480);
    let portrait = image::imageops::rotate270(&camera);
    yarok::platform()
        .world::<DigitOnly>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            format!("interfaces/digit/file=\"{stream}\""),
            "--set".to_owned(),
            "interfaces/digit/size=[640, 480]".to_owned(),
        ])
        .unwrap()
        .behaviour(move |pl| async move {
            let digit: Digit = pl.get("/digit")?;
            let frame = digit.read();
            assert_eq!(frame.dimensions(), (480, 640));
            let turned = mean_difference(&frame, &portrait);
            assert!(turned <= 1.0, "{turned} levels from ffmpeg's, turned");
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn a_real_sensor_without_a_camera_is_an_error_naming_it() {
    let error = yarok::platform()
        .world::<DigitOnly>()
        .args(
            [
                "--env",
                "real",
                "--set",
                r#"interfaces/digit/device="/dev/video97""#,
            ]
            .map(str::to_owned),
        )
        .unwrap()
        .behaviour(|_| async { Ok(()) })
        .run()
        .unwrap_err()
        .to_string();
    assert_says(&error, &["/digit", "/dev/video97"]);
}
