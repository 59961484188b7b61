//! Depth images as the Zenoh bridge carries them (16-bit PNG): read back by Pillow, an
//! independent reader, every depth is the one written to within half its stated unit — a
//! tactile probe's micrometre, so a 2 mm gel spans 2000 levels — in the byte order the PNG
//! standard defines, with the unit in the PNG's own text.

use yarok::components::probe_images::png;
use yarok::core::component::ProbeImage;

use yarok_test::peers;

#[test]
fn depth_pngs_read_back_in_their_unit() {
    // 18 mm (a DIGIT's gel face), 16.3 mm, a 1.2345 mm step, out of range, nothing, NaN.
    let metres = [0.018f32, 0.0163, 0.0012345, 0.1, 0.0, f32::NAN];
    let unit = 1e-6f32;
    let image = ProbeImage::Depth {
        width: metres.len() as u32,
        height: 1,
        metres: metres.to_vec(),
        unit,
    };
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("depth.png");
    std::fs::write(&path, png(&image).unwrap()).unwrap();
    let read = peers::run("png_depth.py", &[path.to_str().unwrap()]);
    assert_eq!(peers::field(&read, "size"), "6 1");
    assert!(peers::field(&read, "mode").starts_with("I;16"), "{read}");
    let stated: f32 = peers::field(&read, "unit").parse().unwrap();
    assert_eq!(stated, unit);
    let counts: Vec<u32> = peers::field(&read, "row")
        .split(' ')
        .map(|v| v.parse().unwrap())
        .collect();
    for (written, count) in metres[..3].iter().zip(&counts) {
        let read_back = *count as f32 * stated;
        assert!(
            (read_back - written).abs() <= unit / 2.0 + 1e-9,
            "{written} m read back as {count} counts of {stated} m"
        );
    }
    assert_eq!(counts[3..], [65535, 0, 0], "out of range, nothing, NaN");
}
