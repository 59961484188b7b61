//! `yarok tactile calibrate`: a sensor's optical model fitted to real frames of ball presses.

use yarok::components::probe_images;
use yarok::components::tactile::calibration::{
    Calibration, Coverage, FitSettings, check_sensor_name, check_setting, held_out, read_presses,
    split_held_out,
};
use yarok::core::output::check_replaceable;

/// Each option's calibration setting, whose physical range bounds it.
const SETTINGS: [(&str, &str); 4] = [
    ("--ball-diameter-mm", "ball_diameter_mm"),
    ("--pixels-per-mm", "pixels_per_mm"),
    ("--contact-scale", "contact_scale"),
    ("--spread", "spread_pixels"),
];

/// The values of a comma-separated list option.
fn numbers(flag: &str, value: &str) -> Result<Vec<f64>, String> {
    value
        .split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v >= 0.0)
                .ok_or_else(|| format!("{flag} {value}: {v:?} is not a non-negative number"))
        })
        .collect()
}

/// Runs `yarok tactile calibrate` with the arguments after `calibrate`.
pub(super) fn run(args: &[String]) -> Result<(), String> {
    let [untouched, presses, out, rest @ ..] = args else {
        return Err(super::USAGE.to_owned());
    };
    let mut settings = FitSettings::default();
    let mut hold_out = 0;
    let mut sensor = None;
    let mut rest = rest.iter();
    while let Some(flag) = rest.next() {
        let value = rest.next().ok_or_else(|| format!("{flag} needs a value"))?;
        if let Some((_, setting)) = SETTINGS.iter().find(|(known, _)| known == flag) {
            for number in numbers(flag, value)? {
                check_setting(setting, number).map_err(|e| format!("{flag} {value}: {e}"))?;
            }
        }
        let single = |flag: &str| -> Result<f64, String> {
            match numbers(flag, value)?[..] {
                [v] if v > 0.0 => Ok(v),
                _ => Err(format!("{flag} {value}: expected one positive number")),
            }
        };
        match flag.as_str() {
            "--ball-diameter-mm" => settings.ball_diameter_mm = single(flag)?,
            "--pixels-per-mm" => settings.pixels_per_mm = single(flag)?,
            "--contact-scale" => settings.contact_scales = numbers(flag, value)?,
            "--spread" => settings.spreads = numbers(flag, value)?,
            "--sensor" => sensor = Some(value.as_str()),
            "--hold-out" => {
                hold_out = value
                    .parse()
                    .map_err(|_| format!("--hold-out {value}: not a whole number"))?
            }
            other => return Err(format!("unknown option {other}\n{}", super::USAGE)),
        }
    }
    let sensor = sensor.ok_or(
        "calibrate needs --sensor NAME (digit, gelsight, or your sensor's own name): a \
         calibration states the sensor it is of, and what loads it checks",
    )?;
    check_sensor_name(sensor).map_err(|e| format!("--sensor {sensor}: {e}"))?;
    super::apart_from_inputs(out, &[untouched, presses])?;
    let background = image::open(untouched)
        .map_err(|e| format!("{untouched}: {e}"))?
        .to_rgb8();
    let map = coverage_map_path(out);
    super::apart_from_inputs(&map, &[untouched, presses])?;
    check_replaceable(map.as_ref(), "PNG image", probe_images::png_by_yarok)
        .map_err(|refused| refused.to_string())?;
    let read = read_presses(presses).map_err(|e| e.to_string())?;
    let names: Vec<String> = read
        .iter()
        .filter(|(name, _)| !held_out(name, hold_out))
        .map(|(name, _)| name.clone())
        .collect();
    let (used, held) = split_held_out(read, hold_out);
    let coverage = Coverage::of(&used, background.width(), background.height());
    let calibration = Calibration::fit(&background, &used, &settings)
        .and_then(|calibration| calibration.for_sensor(sensor))
        .map_err(|e| e.to_string())?;
    calibration.save(out).map_err(|e| e.to_string())?;
    super::write_png(coverage.map(), &map)?;
    let geometry = calibration.geometry();
    let mut report = format!(
        "{out}: fitted to {} of {} presses (contact scale {}, spread {} px)\n",
        used.len(),
        used.len() + held.len(),
        geometry.contact_scale,
        geometry.spread
    );
    let placement = geometry.placement;
    report += &format!(
        "  the imprints lie {:+.1} px across and {:+.1} px down from their described centres, \
         and {:+.1} % (columns) and {:+.1} % (rows) further from the gel's middle\n",
        placement.shift[0],
        placement.shift[1],
        100.0 * placement.stretch[0],
        100.0 * placement.stretch[1]
    );
    for (name, press) in names.iter().zip(&used) {
        let (depth, clamped) = geometry.depth_mm(press.radius);
        report += &format!(
            "  press {name}: radius {:.1} px, depth {depth:.2} mm{}\n",
            press.radius,
            if clamped {
                " (its contact circle would be wider than the ball: taken as the ball sunk to \
                 its equator)"
            } else {
                ""
            }
        );
    }
    report += &format!(
        "{map}: the presses reached {:.0} % of the gel (white; grey: the rest of the rectangle \
         holding them)\n",
        100.0 * coverage.reached_share()
    );
    let [x0, y0, x1, y1] = coverage.rectangle();
    if coverage.outside_share() > UNCOVERED_WARNING {
        report += &format!(
            "warning: no press reached {:.0} % of the gel (outside columns {x0}-{x1}, rows \
             {y0}-{y1}): there the model holds the colour weights of the nearest covered point \
             rather than extrapolating; add presses there\n",
            100.0 * coverage.outside_share()
        );
    }
    super::print(&report)
}

/// The share of the gel outside the presses' rectangle beyond which `calibrate` warns.
const UNCOVERED_WARNING: f64 = 0.25;

/// Where the coverage map of the calibration written to `out` goes: beside it,
/// `NAME.coverage.png`.
fn coverage_map_path(out: &str) -> String {
    let stem = out.strip_suffix(".json").unwrap_or(out);
    format!("{stem}.coverage.png")
}
