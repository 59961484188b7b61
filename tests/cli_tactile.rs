//! `yarok tactile` turns depth maps into tactile images from the command line.

use std::path::PathBuf;
use yarok::components::tactile::calibration::Calibration;

mod support;
use support::yarok_binary;

use yarok_binary::{quick_calibrate, yarok};

fn golden(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden/tactile")
        .join(path)
}

/// The real DIGIT's frames and press list bundled with the project.
fn real_digit() -> String {
    format!(
        "{}/yarok-components/data/tactile-real/digit",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn the_digit_model_from_the_command_line_matches_the_reference() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("digit.png");
    let depth = golden("digit/sphere_center/input_depth.npy.gz");
    let background = golden("digit/background.png");
    let (code, _, stderr) = yarok(&[
        "tactile",
        "digit",
        depth.to_str().unwrap(),
        out.to_str().unwrap(),
        "--background",
        background.to_str().unwrap(),
        "--noise",
        "0",
        "--depth-unit",
        "zbuffer",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let ours = image::open(&out).unwrap().to_rgb8();
    let reference = image::open(golden("digit/sphere_center/output.png"))
        .unwrap()
        .to_rgb8();
    assert_eq!(ours.dimensions(), (240, 320));
    let worst = ours
        .as_raw()
        .iter()
        .zip(reference.as_raw())
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap();
    assert!(worst <= 2, "max difference {worst}");
}

#[test]
fn millimetre_pngs_and_geltip_geometry_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let depth_png = dir.path().join("depth.png");
    let flat =
        image::ImageBuffer::<image::Luma<u16>, _>::from_pixel(320, 240, image::Luma([30u16]));
    flat.save(&depth_png).unwrap();
    let out = dir.path().join("out.png");
    let (code, _, stderr) = yarok(&[
        "tactile",
        "gelsight",
        depth_png.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(
        image::open(&out).unwrap().to_rgb8().dimensions(),
        (320, 240)
    );

    let depth = golden("geltip/sphere_center/input_depth.npy.gz");
    let params = golden("geltip/params");
    let (code, _, stderr) = yarok(&[
        "tactile",
        "geltip",
        depth.to_str().unwrap(),
        out.to_str().unwrap(),
        "--geltip-params",
        params.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(
        image::open(&out).unwrap().to_rgb8().dimensions(),
        (320, 240)
    );
}

/// GelTip needs only the membrane's depth when the light fields are computed.
#[test]
fn geltip_light_fields_are_computed_from_the_membrane() {
    let dir = tempfile::tempdir().unwrap();
    let geometry = dir.path().join("geometry");
    std::fs::create_dir(&geometry).unwrap();
    std::fs::copy(
        golden("geltip/params/bkg_depth_m.npy.gz"),
        geometry.join("bkg_depth_m.npy.gz"),
    )
    .unwrap();
    let render = |case: &str, method: &str| {
        let out = dir.path().join(format!("{case}_{method}.png"));
        let depth = golden(&format!("geltip/{case}/input_depth.npy.gz"));
        let (code, _, stderr) = yarok(&[
            "tactile",
            "geltip",
            depth.to_str().unwrap(),
            out.to_str().unwrap(),
            "--geltip-params",
            geometry.to_str().unwrap(),
            "--light-fields",
            method,
        ]);
        assert_eq!(code, 0, "{stderr}");
        image::open(&out).unwrap().to_rgb8()
    };
    for method in ["linear", "plane"] {
        let (flat, pressed) = (render("flat", method), render("sphere_center", method));
        assert_eq!(flat.dimensions(), (320, 240));
        assert_ne!(flat, pressed, "{method}: the press shows");
    }
    assert_ne!(render("flat", "linear"), render("flat", "plane"));
    let depth = golden("geltip/flat/input_depth.npy.gz");
    let (code, _, stderr) = yarok(&[
        "tactile",
        "geltip",
        depth.to_str().unwrap(),
        dir.path().join("x.png").to_str().unwrap(),
        "--geltip-params",
        geometry.to_str().unwrap(),
    ]);
    assert!(
        code == 2 && stderr.contains("light_field_0.npy.gz"),
        "without --light-fields the files are needed: {stderr}"
    );
}

#[test]
fn mistakes_are_explained() {
    let depth = golden("geltip/sphere_center/input_depth.npy.gz");
    let depth = depth.to_str().unwrap();
    let (code, _, stderr) = yarok(&["tactile", "geltip", depth, "/tmp/x.png"]);
    assert_eq!(
        (code, stderr.trim()),
        (2, "error: geltip needs --geltip-params DIR")
    );
    let (code, _, stderr) = yarok(&[
        "tactile",
        "geltip",
        depth,
        "/tmp/x.png",
        "--light-fields",
        "curved",
    ]);
    assert!(
        code == 2 && stderr.contains("--light-fields curved: expected files, linear or plane"),
        "{stderr}"
    );
    let (code, _, stderr) = yarok(&["tactile", "digits", depth, "/tmp/x.png"]);
    assert!(
        code == 2 && stderr.contains("unknown sensor \"digits\""),
        "{stderr}"
    );
    let (code, _, stderr) = yarok(&["tactile", "digits", "missing.npy", "/tmp/x.png"]);
    assert!(
        code == 2
            && stderr.starts_with(
                "error: unknown sensor \"digits\": digit, gelsight, geltip (or calibrate)"
            ),
        "the sensor is named before any file is read: {stderr}"
    );
    let (code, _, stderr) = yarok(&["tactile", "digit"]);
    assert!(
        code == 2
            && stderr.starts_with(
                "error: yarok tactile needs a sensor, a depth map and an output image"
            ),
        "{stderr}"
    );
    let background = golden("digit/background.png");
    let (code, _, stderr) = yarok(&[
        "tactile",
        "gelsight",
        depth,
        "/tmp/x.png",
        "--background",
        background.to_str().unwrap(),
    ]);
    assert!(
        code == 2 && stderr.contains("is 240×320, the depth map 320×240"),
        "{stderr}"
    );
    let (code, _, stderr) = yarok(&["tactile", "gelsight", "/nonexistent.npy", "/tmp/x.png"]);
    assert!(code == 2 && stderr.contains("/nonexistent.npy"), "{stderr}");
}

/// Writes an uncompressed `.npy` (format 1.0, little-endian f32, C order).
fn write_npy(path: &std::path::Path, rows: usize, columns: usize, data: &[f32]) {
    let mut header =
        format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({rows}, {columns}), }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((header.len() as u16).to_le_bytes());
    bytes.extend(header.as_bytes());
    bytes.extend(data.iter().flat_map(|x| x.to_le_bytes()));
    std::fs::write(path, bytes).unwrap();
}

/// A 16-bit PNG in millimetres gives the same image as a metric `.npy` of the same depths.
#[test]
fn a_millimetre_png_gives_the_same_image_as_the_equivalent_metric_npy() {
    let dir = tempfile::tempdir().unwrap();
    let metric =
        yarok::components::tactile::npy::read(golden("gelsight/sphere_center/input_depth.npy.gz"))
            .unwrap();
    let [rows, columns] = [metric.shape[0], metric.shape[1]];
    let millimetres: Vec<u16> = metric
        .data
        .iter()
        .map(|m| (m * 1000.0).round() as u16)
        .collect();
    let png = dir.path().join("depth_mm.png");
    image::ImageBuffer::<image::Luma<u16>, _>::from_raw(
        columns as u32,
        rows as u32,
        millimetres.clone(),
    )
    .unwrap()
    .save(&png)
    .unwrap();
    let npy = dir.path().join("depth_m.npy");
    let metres: Vec<f32> = millimetres
        .iter()
        .map(|&mm| f32::from(mm) / 1000.0)
        .collect();
    write_npy(&npy, rows, columns, &metres);
    let render = |input: &std::path::Path| {
        let out = dir.path().join("out.png");
        let (code, _, stderr) = yarok(&[
            "tactile",
            "gelsight",
            input.to_str().unwrap(),
            out.to_str().unwrap(),
            "--seed",
            "7",
        ]);
        assert_eq!(code, 0, "{stderr}");
        image::open(&out).unwrap().to_rgb8()
    };
    let (from_png, from_npy) = (render(&png), render(&npy));
    assert_eq!(from_png.dimensions(), (columns as u32, rows as u32));
    assert!(from_png == from_npy, "the two inputs give different images");
}

/// Depth maps and settings that hold no sensible depth are refused with the reason, never
/// turned into an image: an 8-bit or colour PNG, all-NaN or −1e30 depths, an empty render,
/// and texture noise that is not a number from 0 to 1 mm.
#[test]
fn depths_and_noise_that_make_no_sense_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let out = out.to_str().unwrap();
    let grey8 = dir.path().join("grey8.png");
    image::GrayImage::from_pixel(240, 320, image::Luma([30]))
        .save(&grey8)
        .unwrap();
    let rgb = dir.path().join("rgb.png");
    image::RgbImage::from_pixel(240, 320, image::Rgb([30, 30, 30]))
        .save(&rgb)
        .unwrap();
    let nan = dir.path().join("nan.npy");
    write_npy(&nan, 320, 240, &vec![f32::NAN; 320 * 240]);
    let huge = dir.path().join("huge.npy");
    let mut values = vec![0.03f32; 320 * 240];
    values[5 * 240 + 7] = -1e30;
    write_npy(&huge, 320, 240, &values);
    let empty = dir.path().join("empty.npy");
    write_npy(&empty, 320, 240, &vec![0.0; 320 * 240]);
    let good = dir.path().join("good.npy");
    write_npy(&good, 320, 240, &vec![0.03; 320 * 240]);
    let path = |p: &std::path::Path| p.to_str().unwrap().to_owned();
    for (args, expected) in [
        (vec![path(&grey8)], "16-bit grey"),
        (vec![path(&rgb)], "16-bit grey"),
        (vec![path(&nan)], "row 0, column 0 holds NaN"),
        (
            vec![path(&huge)],
            "row 5, column 7 holds -1000000000000000000000000000000",
        ),
        (vec![path(&empty)], "every depth is 0"),
        (
            vec![path(&good), "--noise".into(), "NaN".into()],
            "--noise NaN",
        ),
        (
            vec![path(&good), "--noise".into(), "-1".into()],
            "--noise -1",
        ),
        (
            vec![path(&good), "--noise".into(), "1e308".into()],
            "--noise 1e308",
        ),
    ] {
        let mut all = vec![
            "tactile".to_owned(),
            "digit".to_owned(),
            args[0].clone(),
            out.to_owned(),
        ];
        all.extend(args[1..].iter().cloned());
        let all: Vec<&str> = all.iter().map(String::as_str).collect();
        let (code, _, stderr) = yarok(&all);
        assert_eq!(code, 2, "{all:?}: {stderr}");
        assert!(stderr.contains(expected), "{all:?}: {stderr}");
        assert!(
            !std::path::Path::new(out).exists(),
            "{all:?} wrote an image"
        );
    }
    let (code, _, stderr) = yarok(&["tactile", "digit", &path(&good), out]);
    assert_eq!(code, 0, "{stderr}");
}

#[test]
fn an_output_that_is_one_of_the_inputs_is_refused_and_the_input_kept() {
    let copy = tempfile::tempdir().unwrap();
    let real = real_digit();
    let (untouched, presses) = (
        copy.path().join("background.png"),
        copy.path().join("presses.csv"),
    );
    std::fs::copy(format!("{real}/background.png"), &untouched).unwrap();
    std::fs::copy(format!("{real}/presses.csv"), &presses).unwrap();
    let (untouched, presses) = (untouched.to_str().unwrap(), presses.to_str().unwrap());
    let kept = [
        std::fs::read(untouched).unwrap(),
        std::fs::read(presses).unwrap(),
    ];
    for (out, input) in [(presses, presses), (untouched, untouched)] {
        yarok_binary::yarok_fails(
            &[
                "tactile",
                "calibrate",
                untouched,
                presses,
                out,
                "--sensor",
                "digit",
            ],
            2,
            &[&format!("the output {out} is the input {input}")],
        );
    }
    // `yarok tactile`: the output image is the background it reads.
    let depth = golden("digit/sphere_center/input_depth.npy.gz");
    yarok_binary::yarok_fails(
        &[
            "tactile",
            "digit",
            depth.to_str().unwrap(),
            untouched,
            "--background",
            untouched,
        ],
        2,
        &[&format!("the output {untouched} is the input {untouched}")],
    );
    assert_eq!(std::fs::read(untouched).unwrap(), kept[0]);
    assert_eq!(std::fs::read(presses).unwrap(), kept[1]);
}

/// An image or a calibration at the output path that yarok did not write (a user's photo, the
/// real sensor's frame, a JSON of theirs) is refused and kept byte for byte; what yarok wrote
/// there before is replaced.
#[test]
fn an_output_yarok_did_not_write_is_refused_and_kept() {
    let folder = tempfile::tempdir().unwrap();
    let depth = golden("digit/sphere_center/input_depth.npy.gz");
    let depth = depth.to_str().unwrap();
    let real = real_digit();
    let photo = folder.path().join("photo.png");
    std::fs::copy(format!("{real}/background.png"), &photo).unwrap();
    let photo = photo.to_str().unwrap();
    let notes = folder.path().join("notes.json");
    std::fs::write(&notes, r#"{"format": "my own notes"}"#).unwrap();
    let notes = notes.to_str().unwrap();
    let kept = [std::fs::read(photo).unwrap(), std::fs::read(notes).unwrap()];
    yarok_binary::yarok_fails(
        &["tactile", "digit", depth, photo],
        2,
        &[photo, "is not a PNG image yarok wrote", "another path"],
    );
    let calibrate = quick_calibrate(
        &format!("{real}/background.png"),
        &format!("{real}/presses.csv"),
        notes,
    );
    yarok_binary::yarok_fails(
        &calibrate.iter().map(String::as_str).collect::<Vec<_>>(),
        2,
        &[notes, "is not a calibration yarok wrote"],
    );
    assert_eq!(std::fs::read(photo).unwrap(), kept[0]);
    assert_eq!(std::fs::read(notes).unwrap(), kept[1]);

    let image = folder.path().join("out/image.png");
    let image = image.to_str().unwrap();
    for time in ["first", "second"] {
        let (code, _, stderr) = yarok(&["tactile", "digit", depth, image]);
        assert_eq!(code, 0, "{time} image: {stderr}");
    }
}

/// Presses confined to the lower half of the gel: `calibrate` writes the coverage map beside the
/// calibration and warns naming the share of the gel no press reached and the rows they did.
#[test]
fn calibrate_reports_where_the_presses_reached() {
    let real = real_digit();
    let folder = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(format!("{real}/frames"), folder.path().join("frames")).unwrap();
    let all = std::fs::read_to_string(format!("{real}/presses.csv")).unwrap();
    let lower: Vec<&str> = all
        .lines()
        .enumerate()
        .filter(|(number, line)| {
            *number == 0 || line.split(',').nth(2).unwrap().parse::<f64>().unwrap() >= 150.0
        })
        .map(|(_, line)| line)
        .collect();
    let presses = folder.path().join("lower.csv");
    std::fs::write(&presses, lower.join("\n") + "\n").unwrap();
    let out = folder.path().join("lower.json");
    let calibrate = quick_calibrate(
        &format!("{real}/background.png"),
        presses.to_str().unwrap(),
        out.to_str().unwrap(),
    );
    let (code, stdout, stderr) = yarok(&calibrate.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 0, "{stderr}");
    let map = folder.path().join("lower.coverage.png");
    yarok_test::assert_says(
        &stdout,
        &[&map.display().to_string(), "warning: no press reached"],
    );
    let uncovered: f64 = stdout
        .split("warning: no press reached ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|share| share.parse().ok())
        .unwrap();
    // The presses' rows start below the upper half's.
    let rows = stdout.split(", rows ").nth(1).unwrap();
    let first_row: u32 = rows.split('-').next().unwrap().parse().unwrap();
    assert!(uncovered > 50.0 && first_row >= 90, "{stdout}");
    // Each press's depth: a 0.7 contact circle of a 49-55 px imprint on the 4.7 mm ball at
    // 19.58 px/mm sinks it 1.3-1.7 mm by Hertz's law, short of its equator (2.35 mm), wider ones
    // deeper.
    let depths: Vec<f64> = stdout
        .lines()
        .filter(|line| line.trim_start().starts_with("press "))
        .map(|line| {
            let depth = line.split("depth ").nth(1).unwrap();
            depth.split(' ').next().unwrap().parse().unwrap()
        })
        .collect();
    assert_eq!(depths.len(), lower.len() - 1, "{stdout}");
    assert!(depths.iter().all(|d| (1.0..=1.7).contains(d)), "{stdout}");
    let spread =
        depths.iter().copied().fold(0.0, f64::max) - depths.iter().copied().fold(9.0, f64::min);
    assert!(spread > 0.2, "{stdout}");
    assert!(!stdout.contains("equator"), "{stdout}");
    let map = image::open(&map).unwrap().to_rgb8();
    assert_eq!(map.dimensions(), (240, 320));
    assert_eq!(map.get_pixel(120, 10).0, [0; 3], "the top row is outside");
    assert_eq!(
        map.get_pixel(120, 200).0,
        [255; 3],
        "the lower middle is reached"
    );
}

/// A contact scale that would make a press's contact circle wider than the ball is no press a
/// ball can make: refused, naming the largest scale the presses allow.
#[test]
fn calibrate_refuses_a_contact_circle_wider_than_the_ball() {
    let real = real_digit();
    let out = tempfile::tempdir().unwrap();
    let written = out.path().join("c.json");
    yarok_binary::yarok_fails(
        &[
            "tactile",
            "calibrate",
            &format!("{real}/background.png"),
            &format!("{real}/presses.csv"),
            written.to_str().unwrap(),
            "--sensor",
            "digit",
            "--contact-scale",
            "1.2",
        ],
        2,
        &[
            "with contact scale 1.2 the widest press's contact circle (54.6 px × the scale) is \
             wider than the 4.7 mm ball (46.0 px at 19.58 px/mm)",
            "at most 0.843",
        ],
    );
    assert!(!written.exists());
}

#[test]
fn calibration_settings_outside_their_physical_range_are_refused_before_fitting() {
    let real = real_digit();
    let out = tempfile::tempdir().unwrap();
    let written = out.path().join("c.json");
    let (untouched, presses) = (
        format!("{real}/background.png"),
        format!("{real}/presses.csv"),
    );
    for (flag, value, said) in [
        (
            "--spread",
            "1e9",
            "spread_pixels 1e9 is outside its physical range, 0 to 64",
        ),
        (
            "--pixels-per-mm",
            "1e9",
            "pixels_per_mm 1e9 is outside its physical range",
        ),
        (
            "--contact-scale",
            "0.9,1e300",
            "contact_scale 1e300 is outside",
        ),
        (
            "--ball-diameter-mm",
            "0.01",
            "ball_diameter_mm 0.01 is outside",
        ),
    ] {
        let started = std::time::Instant::now();
        yarok_binary::yarok_fails(
            &[
                "tactile",
                "calibrate",
                &untouched,
                &presses,
                written.to_str().unwrap(),
                "--sensor",
                "digit",
                flag,
                value,
            ],
            2,
            &[&format!("{flag} {value}: {said}")],
        );
        assert!(started.elapsed().as_secs() < 10, "{flag} {value} took long");
        assert!(!written.exists());
    }
    // A calibration file holding such a spread is refused naming it.
    let bundled = std::fs::read_to_string(format!(
        "{}/yarok-components/src/tactile/calibration/digit.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let file = out.path().join("wide.json");
    std::fs::write(&file, {
        let spread = format!(
            "\"spread_pixels\": {:?}",
            Calibration::digit().geometry().spread
        );
        assert!(bundled.contains(&spread), "{spread}");
        bundled.replace(&spread, "\"spread_pixels\": 1e9")
    })
    .unwrap();
    let depth = golden("digit/sphere_center/input_depth.npy.gz");
    yarok_binary::yarok_fails(
        &[
            "tactile",
            "digit",
            depth.to_str().unwrap(),
            out.path().join("o.png").to_str().unwrap(),
            "--calibration",
            file.to_str().unwrap(),
        ],
        2,
        &["spread_pixels 1e9 is outside its physical range, 0 to 64"],
    );
}

/// A press list read by its header: columns in another order read the same presses; a list
/// without a header, a frame named twice, a radius or centre that no frame has, and a grey
/// frame among colour ones are refused naming the file and line (and the CLI exits 2 on them,
/// writing nothing).
#[test]
fn press_lists_are_read_by_their_header_and_checked() {
    use yarok::components::tactile::calibration::read_presses;

    let real = real_digit();
    let original = std::fs::read_to_string(format!("{real}/presses.csv")).unwrap();
    let rows: Vec<Vec<&str>> = original
        .lines()
        .map(|line| line.split(',').collect())
        .collect();
    let folder = tempfile::tempdir().unwrap();
    std::fs::create_dir(folder.path().join("frames")).unwrap();
    for entry in std::fs::read_dir(format!("{real}/frames")).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(
            entry.path(),
            folder.path().join("frames").join(entry.file_name()),
        )
        .unwrap();
    }
    let list = |name: &str, text: String| {
        let path = folder.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_owned()
    };
    let reordered = list(
        "reordered.csv",
        rows.iter()
            .map(|r| format!("{},{},{},{}\n", r[3], r[0], r[2], r[1]))
            .collect(),
    );
    let read = |path: &str| -> Vec<(String, [f64; 2], f64)> {
        read_presses(path)
            .unwrap()
            .into_iter()
            .map(|(name, press)| (name, press.centre, press.radius))
            .collect()
    };
    assert_eq!(read(&reordered), read(&format!("{real}/presses.csv")));
    let lines: Vec<&str> = original.lines().collect();
    let first_frame = rows[1][0];
    // A grey copy of the second frame, under a name of its own.
    let second = image::open(format!("{real}/frames/{}.png", rows[2][0])).unwrap();
    second
        .to_luma8()
        .save(folder.path().join("frames/grey.png"))
        .unwrap();
    let cases = [
        (
            "headless.csv",
            lines[1..].join("\n"),
            "headless.csv:1: the header must name the columns frame, center_x, center_y, \
             radius_px (in any order)",
        ),
        (
            "twice.csv",
            format!("{}\n{}\n{}\n", lines[0], lines[1], lines[1]),
            &*format!("twice.csv:3: frame \"{first_frame}\" is on line 2 already"),
        ),
        (
            "huge.csv",
            format!("{}\n{first_frame},140,148,1e30\n", lines[0]),
            "huge.csv:2: radius_px 1000000000000000000000000000000 is not between 1 and 160",
        ),
        (
            "off.csv",
            format!("{}\n{first_frame},-5,148,40\n", lines[0]),
            "off.csv:2: centre (-5, 148) is off its 240×320 frame",
        ),
        (
            "grey.csv",
            format!("{}\n{}\ngrey,140,148,40\n", lines[0], lines[1]),
            "grey.csv:3: frame",
        ),
    ];
    let out = folder.path().join("out.json");
    for (name, text, said) in cases {
        let path = list(name, text);
        let error = read_presses(&path).unwrap_err().to_string();
        assert!(error.contains(said), "{error}");
        yarok_binary::yarok_fails(
            &[
                "tactile",
                "calibrate",
                &format!("{real}/background.png"),
                &path,
                out.to_str().unwrap(),
                "--sensor",
                "digit",
            ],
            2,
            &[said],
        );
        assert!(!out.exists());
    }
    let grey = read_presses(&folder.path().join("grey.csv").to_string_lossy())
        .unwrap_err()
        .to_string();
    assert!(
        grey.contains("is 240×320 grey where the first frame is 240×320 colour"),
        "{grey}"
    );
}

/// A calibration states the sensor it is of: `calibrate` asks for it, and a DIGIT's calibration
/// given to `yarok tactile gelsight` is refused naming both.
#[test]
fn a_calibration_is_of_one_sensor() {
    let real = real_digit();
    let out = tempfile::tempdir().unwrap();
    let written = out.path().join("c.json");
    yarok_binary::yarok_fails(
        &[
            "tactile",
            "calibrate",
            &format!("{real}/background.png"),
            &format!("{real}/presses.csv"),
            written.to_str().unwrap(),
        ],
        2,
        &["calibrate needs --sensor NAME (digit, gelsight, or your sensor's own name)"],
    );
    assert!(!written.exists());
    let digit = format!(
        "{}/yarok-components/src/tactile/calibration/digit.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let depth = golden("digit/sphere_center/input_depth.npy.gz");
    let image = out.path().join("gelsight.png");
    yarok_binary::yarok_fails(
        &[
            "tactile",
            "gelsight",
            depth.to_str().unwrap(),
            image.to_str().unwrap(),
            "--calibration",
            &digit,
        ],
        2,
        &[&format!(
            "{digit}: a calibration of a digit sensor, not of a gelsight: calibrate the \
             gelsight (yarok tactile calibrate … --sensor gelsight)"
        )],
    );
    assert!(!image.exists());
}

/// A `.npy` depth map is in metres for every sensor, as `--help` says: a flat DIGIT gel at
/// 0.030 m (untouched) renders as its background, not near-black; the reference model's raw
/// z-buffer values are read with `--depth-unit zbuffer`.
#[test]
fn a_npy_depth_map_is_in_metres_for_the_digit_too() {
    let dir = tempfile::tempdir().unwrap();
    let npy = dir.path().join("flat.npy");
    write_npy(&npy, 320, 240, &vec![0.030; 320 * 240]);
    let background = golden("digit/background.png");
    let out = dir.path().join("flat.png");
    let (code, _, stderr) = yarok(&[
        "tactile",
        "digit",
        npy.to_str().unwrap(),
        out.to_str().unwrap(),
        "--background",
        background.to_str().unwrap(),
        "--noise",
        "0",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let image = image::open(&out).unwrap().to_rgb8();
    let reference = image::open(&background).unwrap().to_rgb8();
    let mean_difference = image
        .as_raw()
        .iter()
        .zip(reference.as_raw())
        .map(|(a, b)| f64::from(a.abs_diff(*b)))
        .sum::<f64>()
        / image.as_raw().len() as f64;
    assert!(
        mean_difference < 5.0,
        "{mean_difference} levels from the background"
    );
    yarok_binary::yarok_fails(
        &[
            "tactile",
            "gelsight",
            npy.to_str().unwrap(),
            out.to_str().unwrap(),
            "--depth-unit",
            "zbuffer",
        ],
        2,
        &["--depth-unit zbuffer is for a .npy map given to the reference DIGIT model"],
    );
}
