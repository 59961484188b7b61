//! What `yarok tactile calibrate` reads, on generated input: press lists (columns reordered,
//! rows repeated, numbers of every size, fields missing, bytes flipped), calibration files
//! (valid ones mutated) and settings. 100 000 inputs each (`YAROK_FUZZ_INPUTS` sets how many):
//! each is read or refused with a message naming the file, none panics, and what is read holds
//! what the reader promises (centres on their frames, radii between a pixel and half the frame,
//! every frame once); every hundredth list read is fitted, within a bound.

use std::path::Path;
use std::time::{Duration, Instant};

use image::RgbImage;
use yarok_components::tactile::calibration::{
    Calibration, CalibrationError, FitSettings, check_setting, read_presses,
};
use yarok_test::generator::{Generator, fuzz_inputs};

/// The frames' size: small, so that a hundred thousand lists read in seconds.
const SIZE: (u32, u32) = (24, 16);

/// The longest a fit of these small frames may take.
const FIT_BOUND: Duration = Duration::from_secs(5);

/// The untouched gel and six frames of presses: 0000–0003 of one size and colour, 0004 grey and
/// 0005 of another size.
fn frames(folder: &Path) -> RgbImage {
    let (width, height) = SIZE;
    let untouched = RgbImage::from_fn(width, height, |x, y| {
        image::Rgb([100 + x as u8, 120 + y as u8, 140])
    });
    std::fs::create_dir_all(folder.join("frames")).unwrap();
    for press in 0..4u32 {
        let frame = RgbImage::from_fn(width, height, |x, y| {
            let near = (x as i32 - 6 - 3 * press as i32).pow(2) + (y as i32 - 8).pow(2) < 16;
            let base = untouched.get_pixel(x, y).0;
            image::Rgb(if near { base.map(|c| c / 2) } else { base })
        });
        frame
            .save(folder.join(format!("frames/{press:04}.png")))
            .unwrap();
    }
    image::GrayImage::new(width, height)
        .save(folder.join("frames/0004.png"))
        .unwrap();
    RgbImage::new(width + 2, height)
        .save(folder.join("frames/0005.png"))
        .unwrap();
    untouched
}

/// A press list's field: plausible, extreme or nonsense.
fn field(generator: &mut Generator) -> String {
    let fields = [
        "0000", "0001", "0002", "0003", "0004", "0005", "0006", "8", "6.5", "3", "1", "0", "-1",
        "12", "16", "24", "1e308", "-1e308", "NaN", "inf", "", " ", "../0000", ".hidden", "0x10",
        "1,5", "\"0001\"", "ü",
    ];
    generator.pick(&fields).to_owned()
}

/// A press list, generated from the columns' names and fields, then perhaps mutated.
fn press_list(generator: &mut Generator) -> String {
    let mut columns = vec!["frame", "center_x", "center_y", "radius_px"];
    if generator.below(4) == 0 {
        columns.swap(generator.below(4), generator.below(4));
    }
    match generator.below(12) {
        0 => {
            let at = generator.below(columns.len());
            columns.remove(at);
        }
        1 => columns.push("note"),
        2 => columns.push("frame"),
        _ => {}
    }
    let mut text = String::new();
    if generator.below(15) != 0 {
        text += &columns.join(",");
        text.push('\n');
    }
    for _ in 0..generator.below(5) {
        let row: Vec<String> = columns
            .iter()
            .map(|column| match (*column, generator.below(3)) {
                ("frame", 0 | 1) => format!("{:04}", generator.below(4)),
                ("center_x", 0 | 1) => format!("{}", generator.below(30)),
                ("center_y", 0 | 1) => format!("{}", generator.below(20)),
                ("radius_px", 0 | 1) => format!("{}", 1 + generator.below(12)),
                _ => field(generator),
            })
            .collect();
        let mut row = row.join(",");
        if generator.below(20) == 0 {
            row.push(',');
        }
        text += &row;
        text.push_str(if generator.below(10) == 0 {
            "\r\n"
        } else {
            "\n"
        });
    }
    let mut bytes = text.into_bytes();
    if generator.below(10) == 0 && !bytes.is_empty() {
        let at = generator.below(bytes.len());
        bytes[at] = generator.next_u64() as u8;
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

#[test]
fn generated_press_lists_are_read_within_their_promises_or_refused() {
    let folder = tempfile::tempdir().unwrap();
    let untouched = frames(folder.path());
    let csv = folder.path().join("presses.csv");
    let csv = csv.to_str().unwrap();
    let mut generator = Generator(0x000c_a11b_8a7e);
    let (mut read, mut refused, mut fitted) = (0, 0, 0);
    for _ in 0..fuzz_inputs() {
        std::fs::write(csv, press_list(&mut generator)).unwrap();
        let presses = match read_presses(csv) {
            Ok(presses) => presses,
            Err(error) => {
                assert!(error.to_string().contains(csv), "{error}");
                refused += 1;
                continue;
            }
        };
        read += 1;
        let Some(size) = presses.first().map(|(_, press)| press.frame.dimensions()) else {
            continue;
        };
        let (width, height) = (f64::from(size.0), f64::from(size.1));
        for (name, press) in &presses {
            assert_eq!(press.frame.dimensions(), size, "{name}");
            let [x, y] = press.centre;
            assert!((0.0..=width).contains(&x) && (0.0..=height).contains(&y));
            assert!(
                (1.0..=width / 2.0).contains(&press.radius),
                "{}",
                press.radius
            );
            assert_eq!(presses.iter().filter(|(other, _)| other == name).count(), 1);
        }
        if read % 100 == 1 && !presses.is_empty() {
            let presses: Vec<_> = presses.into_iter().map(|(_, press)| press).collect();
            let settings = FitSettings {
                ball_diameter_mm: 4.7,
                pixels_per_mm: 1.0 + generator.below(30) as f64,
                contact_scales: vec![0.05 + generator.below(30) as f64 / 10.0],
                spreads: vec![generator.below(65) as f64],
                placement: None,
            };
            let started = Instant::now();
            match Calibration::fit(&untouched, &presses, &settings) {
                Ok(_) => fitted += 1,
                Err(CalibrationError::Fit(reason)) => assert!(!reason.to_string().is_empty()),
                Err(other) => panic!("a fit failed with {other}"),
            }
            assert!(started.elapsed() < FIT_BOUND, "{settings:?}");
        }
    }
    eprintln!("{read} press lists read ({fitted} fitted), {refused} refused");
    assert!(
        read > fuzz_inputs() / 20 && refused > fuzz_inputs() / 2,
        "{read} read, {refused} refused"
    );
}

/// A valid calibration's JSON changed in one of several ways.
fn mutate(valid: &str, generator: &mut Generator) -> String {
    let mut text = valid.to_owned();
    match generator.below(5) {
        0 => {
            let at = generator.below(text.len());
            text.truncate(text.floor_char_boundary(at));
        }
        1 => {
            // A number replaced by an extreme or a wrong one.
            let numbers: Vec<usize> = text
                .char_indices()
                .filter(|(i, c)| c.is_ascii_digit() && !text[..*i].ends_with(char::is_alphanumeric))
                .map(|(i, _)| i)
                .collect();
            if let Some(&at) = numbers.get(generator.below(numbers.len().max(1))) {
                let end = text[at..]
                    .find(|c: char| !(c.is_ascii_digit() || ".e-+".contains(c)))
                    .map_or(text.len(), |e| at + e);
                let replacement = ["1e308", "-1e300", "0", "-1", "1e9", "4294967296", "\"x\""]
                    [generator.below(7)];
                text.replace_range(at..end, replacement);
            }
        }
        2 => {
            let fields = [
                "\"sensor\": \"gelsight\",",
                "\"width\": 0,",
                "\"extra\": 1,",
            ];
            let at = text.find('\n').unwrap_or(0) + 1;
            text.insert_str(at, generator.pick(&fields));
        }
        3 => {
            let mut bytes = text.into_bytes();
            for _ in 0..=generator.below(4) {
                let at = generator.below(bytes.len());
                bytes[at] = generator.next_u64() as u8;
            }
            text = String::from_utf8_lossy(&bytes).into_owned();
        }
        _ => {
            // A field's value removed.
            if let Some(line) = text.lines().nth(1 + generator.below(12)).map(str::to_owned) {
                text = text.replacen(&line, "", 1);
            }
        }
    }
    text
}

#[test]
fn mutated_calibration_files_are_loaded_within_bounds_or_refused() {
    let folder = tempfile::tempdir().unwrap();
    let untouched = frames(folder.path());
    let csv = folder.path().join("presses.csv");
    std::fs::write(
        &csv,
        "frame,center_x,center_y,radius_px\n0000,6,8,4\n0001,9,8,4\n0002,12,8,4\n",
    )
    .unwrap();
    let presses: Vec<_> = read_presses(csv.to_str().unwrap())
        .unwrap()
        .into_iter()
        .map(|(_, press)| press)
        .collect();
    let settings = FitSettings {
        pixels_per_mm: 2.0,
        contact_scales: vec![0.9],
        spreads: vec![2.0],
        ..FitSettings::default()
    };
    let valid = Calibration::fit(&untouched, &presses, &settings)
        .unwrap()
        .for_sensor("digit")
        .unwrap()
        .to_json();
    let path = folder.path().join("calibration.json");
    let path = path.to_str().unwrap();
    let mut generator = Generator(0x0f11_eca1);
    let (mut loaded, mut refused) = (0, 0);
    for _ in 0..fuzz_inputs() {
        std::fs::write(path, mutate(&valid, &mut generator)).unwrap();
        match Calibration::load(path) {
            Ok(calibration) => {
                loaded += 1;
                let geometry = calibration.geometry();
                for (name, value) in [
                    ("pixels_per_mm", geometry.pixels_per_mm),
                    ("ball_diameter_mm", geometry.ball_diameter_mm),
                    ("contact_scale", geometry.contact_scale),
                    ("spread_pixels", geometry.spread),
                ] {
                    check_setting(name, value).unwrap();
                }
            }
            Err(error) => {
                assert!(error.to_string().contains(path), "{error}");
                refused += 1;
            }
        }
    }
    eprintln!("{loaded} calibrations loaded, {refused} refused");
    assert!(
        refused > fuzz_inputs() / 2,
        "{loaded} loaded, {refused} refused"
    );
}

#[test]
fn generated_settings_are_checked_against_their_ranges() {
    let mut generator = Generator(0x005e_771e);
    let names = [
        "ball_diameter_mm",
        "pixels_per_mm",
        "contact_scale",
        "spread_pixels",
        "radius",
    ];
    for _ in 0..fuzz_inputs() {
        let name = generator.pick(&names);
        let bits = generator.next_u64();
        let value = match generator.below(3) {
            0 => f64::from_bits(bits),
            1 => (bits % 100_000) as f64 / 100.0 - 10.0,
            _ => [f64::NAN, f64::INFINITY, -0.0, 1e308, 64.0, 64.000_001][generator.below(6)],
        };
        match check_setting(name, value) {
            Ok(()) => assert!(value.is_finite() && value >= 0.0, "{name} {value}"),
            Err(error) => assert!(
                error.to_string().contains(name) || name == "radius",
                "{error}"
            ),
        }
    }
}
