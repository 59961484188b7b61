//! Camera frames made by a third-party encoder (Debian's `ffmpeg`, its `testsrc` pattern)
//! decoded as ffmpeg itself decodes them: MJPEG streams from a file and live from ffmpeg's
//! output, and YUYV frames, each within a mean of 1 level of ffmpeg's RGB; bad input an error.
#![cfg(feature = "camera")]

use std::process::{Command, Stdio};

use yarok_hw::camera::{DecodeError, MjpegStream, PixelFormat, StreamError, decode};

const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;

/// Runs ffmpeg with `args`, returning what it writes to its output.
fn ffmpeg(args: &[&str]) -> Vec<u8> {
    let output = Command::new("ffmpeg")
        .args(["-hide_banner", "-loglevel", "error"])
        .args(args)
        .output()
        .expect("ffmpeg runs (scripts/setup-test-peers.sh installs it)");
    yarok_test::assert_succeeded(&output);
    output.stdout
}

/// `frames` frames of ffmpeg's test pattern as `format` (an ffmpeg muxer and pixel format).
fn pattern(frames: u32, muxer: &[&str]) -> Vec<u8> {
    let source = format!("testsrc=size={WIDTH}x{HEIGHT}:rate=10");
    let frames = frames.to_string();
    let mut args = vec!["-f", "lavfi", "-i", &source, "-frames:v", &frames];
    args.extend_from_slice(muxer);
    args.push("pipe:1");
    ffmpeg(&args)
}

/// ffmpeg's own RGB decode of `input` (given as a file of `format`).
fn ffmpeg_rgb(input: &[u8], format: &[&str]) -> Vec<u8> {
    let mut file = tempfile::NamedTempFile::new().unwrap();
    std::io::Write::write_all(&mut file, input).unwrap();
    let path = file.path().to_str().unwrap().to_owned();
    let mut args: Vec<&str> = format.to_vec();
    args.extend_from_slice(&["-i", &path, "-f", "rawvideo", "-pix_fmt", "rgb24", "pipe:1"]);
    ffmpeg(&args)
}

fn mean_difference(ours: &[u8], theirs: &[u8]) -> f64 {
    assert_eq!(ours.len(), theirs.len());
    let total: u64 = ours
        .iter()
        .zip(theirs)
        .map(|(a, b)| u64::from(a.abs_diff(*b)))
        .sum();
    total as f64 / ours.len() as f64
}

#[tokio::test]
async fn an_mjpeg_stream_decodes_as_ffmpeg_decodes_it() {
    let stream = pattern(5, &["-f", "mjpeg", "-q:v", "3"]);
    let reference = ffmpeg_rgb(&stream, &["-f", "mjpeg"]);
    let frame_bytes = (3 * WIDTH * HEIGHT) as usize;
    assert_eq!(reference.len(), 5 * frame_bytes);
    let mut frames = MjpegStream::new(stream.as_slice(), "testsrc", WIDTH, HEIGHT);
    for index in 0..5 {
        let frame = frames.next_frame().await.unwrap().expect("a frame");
        let theirs = &reference[index * frame_bytes..(index + 1) * frame_bytes];
        let difference = mean_difference(frame.as_raw(), theirs);
        eprintln!("MJPEG frame {index}: mean difference from ffmpeg {difference:.3}");
        assert!(
            difference <= 1.0,
            "frame {index}: mean difference {difference}"
        );
    }
    assert!(
        frames.next_frame().await.unwrap().is_none(),
        "five frames, then the end"
    );
}

#[tokio::test]
async fn frames_come_live_from_a_pipe() {
    let source = format!("testsrc=size={WIDTH}x{HEIGHT}:rate=30");
    let mut encoder = tokio::process::Command::new("ffmpeg")
        .args([
            "-hide_banner",
            "-loglevel",
            "error",
            "-re",
            "-f",
            "lavfi",
            "-i",
            &source,
        ])
        .args(["-frames:v", "10", "-f", "mjpeg", "pipe:1"])
        .stdout(Stdio::piped())
        .kill_on_drop(true)
        .spawn()
        .expect("ffmpeg runs");
    let mut frames = MjpegStream::new(encoder.stdout.take().unwrap(), "ffmpeg", WIDTH, HEIGHT);
    let mut count = 0;
    while let Some(frame) = frames.next_frame().await.unwrap() {
        assert_eq!(frame.dimensions(), (WIDTH, HEIGHT));
        count += 1;
    }
    assert_eq!(count, 10);
    assert!(encoder.wait().await.unwrap().success());
}

#[test]
fn yuyv_decodes_as_ffmpeg_decodes_it() {
    let yuyv = pattern(1, &["-f", "rawvideo", "-pix_fmt", "yuyv422"]);
    let size = format!("{WIDTH}x{HEIGHT}");
    let reference = ffmpeg_rgb(
        &yuyv,
        &["-f", "rawvideo", "-pix_fmt", "yuyv422", "-s", &size],
    );
    let ours = decode(PixelFormat::Yuyv, WIDTH, HEIGHT, &yuyv).unwrap();
    let difference = mean_difference(ours.as_raw(), &reference);
    eprintln!("YUYV: mean difference from ffmpeg {difference:.3}");
    assert!(difference <= 1.0, "mean difference {difference}");
}

#[tokio::test]
async fn bad_frames_are_errors_not_panics() {
    let yuyv = decode(PixelFormat::Yuyv, WIDTH, HEIGHT, &[0; 10]).unwrap_err();
    assert!(matches!(yuyv, DecodeError::Size { .. }), "{yuyv}");
    let jpeg = decode(
        PixelFormat::Mjpeg,
        WIDTH,
        HEIGHT,
        &[0xFF, 0xD8, 1, 2, 3, 0xFF, 0xD9],
    );
    assert!(matches!(jpeg, Err(DecodeError::Jpeg { .. })), "{jpeg:?}");
    let stream = pattern(1, &["-f", "mjpeg"]);
    let wrong_size = decode(PixelFormat::Mjpeg, 640, 480, &stream).unwrap_err();
    assert!(wrong_size.to_string().contains("320x240"), "{wrong_size}");
    // A stream that is not MJPEG ends, or fails naming the camera; it never hangs.
    let noise: Vec<u8> = (0..100_000u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8)
        .collect();
    let mut frames = MjpegStream::new(noise.as_slice(), "noise", WIDTH, HEIGHT);
    loop {
        match frames.next_frame().await {
            Ok(None) => break,
            Ok(Some(_)) => panic!("noise decoded as a frame"),
            Err(StreamError::Decode { camera, .. }) => assert_eq!(camera, "noise"),
            Err(error) => panic!("{error}"),
        }
    }
}
