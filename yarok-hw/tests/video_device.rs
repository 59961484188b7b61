//! Video4Linux2 capture (feature `camera`) where there is no camera: this machine's kernel has
//! no V4L2, so what can be checked is that a missing device, a device that is no camera and a
//! plain file are each refused with an error naming them (capture itself is covered by the
//! decoders' tests against ffmpeg, and runs on a machine with a camera).
#![cfg(feature = "camera")]

use yarok_hw::camera::{CaptureError, VideoDevice};

#[test]
fn what_is_not_a_camera_is_refused_naming_it() {
    let missing = VideoDevice::open("/dev/video97", 640, 480, 30).unwrap_err();
    assert!(matches!(missing, CaptureError::Open { .. }), "{missing}");
    assert!(missing.to_string().contains("/dev/video97"), "{missing}");

    let null = VideoDevice::open("/dev/null", 640, 480, 30).unwrap_err();
    assert!(matches!(null, CaptureError::NotACamera { .. }), "{null}");
    assert!(null.to_string().contains("/dev/null"), "{null}");

    let file = tempfile::NamedTempFile::new().unwrap();
    let path = file.path().to_str().unwrap();
    let plain = VideoDevice::open(path, 320, 240, 60).unwrap_err();
    assert!(matches!(plain, CaptureError::NotACamera { .. }), "{plain}");
    assert!(plain.to_string().contains(path), "{plain}");
}
