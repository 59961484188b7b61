//! `Cam` with `--env real` (feature `camera`): frames of an MJPEG stream from a program it runs
//! (here ffmpeg's moving test pattern, as it would capture a USB camera), newest first, no depth;
//! the program is stopped when the run ends; a bad source (a missing program, file or
//! Video4Linux2 device, a device that is no camera) is an error naming the component.
#![cfg(feature = "camera")]

use yarok::components::cameras::{Cam, CamError};
use yarok::{Component, Declaration};
use yarok_test::assert_says;

/// One 320×240 camera.
struct CameraOnly;

impl Component for CameraOnly {
    fn declaration() -> Declaration {
        Declaration::new("camera_only").uses::<Cam>().template(
            r#"<mujoco><worldbody><cam name="cam" width="320" height="240"/></worldbody></mujoco>"#,
        )
    }
}

/// A test-pattern source only this test uses, so that its process can be found.
const PATTERN: &str = "testsrc=size=320x240:rate=29";

#[test]
fn a_real_camera_shows_the_newest_frame_of_its_stream() {
    let command = format!(
        r#"interfaces/cam/command=["ffmpeg", "-hide_banner", "-loglevel", "error", "-re", "-f", "lavfi", "-i", "{PATTERN}", "-f", "mjpeg", "pipe:1"]"#
    );
    yarok::platform()
        .world::<CameraOnly>()
        .args([
            "--env".to_owned(),
            "real".to_owned(),
            "--set".to_owned(),
            command,
        ])
        .unwrap()
        .behaviour(|pl| async move {
            let cam: Cam = pl.get("/cam")?;
            let first = cam.read()?;
            assert_eq!(first.dimensions(), (320, 240));
            // The pattern moves: a newer frame comes (within seconds, however busy the machine).
            pl.wait(|| cam.read().is_ok_and(|frame| frame != first))
                .timeout(5.0)
                .await?;
            assert!(matches!(cam.read_depth(), Err(CamError::NoDepth)));
            Ok(())
        })
        .run()
        .unwrap();
    let left = std::process::Command::new("pgrep")
        .args(["-f", PATTERN])
        .output()
        .unwrap();
    assert!(
        left.stdout.is_empty(),
        "ffmpeg still runs: {:?}",
        String::from_utf8_lossy(&left.stdout)
    );
}

#[test]
fn a_bad_source_is_an_error_naming_the_camera() {
    for setting in [
        r#"interfaces/cam/command=["no-such-program-yarok"]"#,
        r#"interfaces/cam/file="/no/such/stream.mjpeg""#,
        r#"interfaces/cam/first_frame_seconds=1"#,
    ] {
        let error = yarok::platform()
            .world::<CameraOnly>()
            .args(["--env", "real", "--set", setting].map(str::to_owned))
            .unwrap()
            .behaviour(|_| async { Ok(()) })
            .run()
            .unwrap_err()
            .to_string();
        assert!(error.contains("/cam"), "{setting}: {error}");
    }
    for (device, says) in [
        ("/dev/video97", "No such file"),
        ("/dev/null", "not a video capture device"),
    ] {
        let error = yarok::platform()
            .world::<CameraOnly>()
            .args([
                "--env".into(),
                "real".into(),
                "--set".into(),
                format!("interfaces/cam/device=\"{device}\""),
            ])
            .unwrap()
            .behaviour(|_| async { Ok(()) })
            .run()
            .unwrap_err()
            .to_string();
        assert_says(&error, &["/cam", device, says]);
    }
}
