//! Parity with the reference implementation on the golden cases in `tests/golden/tactile`
//! (noise off): per channel max |ours − ref| ≤ 1, mean ≤ 0.1, as the README claims (the reference's
//! own criterion is looser: max ≤ 2, at most 0.5 % of pixels off by > 1).

use std::path::PathBuf;

use yarok_components::tactile::npy;
use yarok_components::tactile::phong::{PhongModel, PhongParams};

fn golden() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/golden/tactile")
}

fn png_rgb(path: PathBuf) -> (u32, u32, Vec<u8>) {
    let image = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8();
    (image.width(), image.height(), image.into_raw())
}

fn cases(model: &str) -> Vec<String> {
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(golden().join("index.json")).unwrap())
            .unwrap();
    index["models"][model]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["case"].as_str().unwrap().to_owned())
        .collect()
}

/// Asserts what the README claims: every channel of every pixel within 1 level of the reference,
/// the mean difference per channel at most 0.1 level.
fn assert_matches(label: &str, ours: &[u8], reference: &[u8]) {
    assert_eq!(ours.len(), reference.len(), "{label}: image sizes differ");
    assert!(!ours.is_empty(), "{label}: empty image");
    let pixels = ours.len() / 3;
    for channel in 0..3 {
        let diffs = (0..pixels).map(|i| ours[3 * i + channel].abs_diff(reference[3 * i + channel]));
        let max = diffs.clone().max().unwrap();
        let mean = diffs.map(f64::from).sum::<f64>() / pixels as f64;
        eprintln!("{label} channel {channel}: max {max}, mean {mean:.4}");
        assert!(
            max <= 1 && mean <= 0.1,
            "{label} channel {channel}: max {max}, mean {mean:.4}"
        );
    }
}

fn check(model: &str, params: PhongParams, light_key: &str) {
    let mut phong = PhongModel::new(params.clone());
    let (width, height, background) = png_rgb(golden().join(model).join("background.png"));
    for case in cases(model) {
        let dir = golden().join(model).join(&case);
        let manifest: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).unwrap())
                .unwrap();
        let p = &manifest["parameters"];
        assert_eq!(p["ka"].as_f64(), Some(params.ka), "{model}/{case}: ka");
        assert_eq!(
            p["elastomer_thickness"].as_f64(),
            Some(params.elastomer_thickness)
        );
        assert_eq!(p["min_depth"].as_f64(), Some(params.min_depth));
        let lights = p["light_sources"].as_array().unwrap();
        assert_eq!(params.lights.len(), lights.len(), "{model}/{case}: lights");
        for (light, reference) in params.lights.iter().zip(lights) {
            let native: Vec<f64> = reference[light_key]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            let rgb = if light_key == "color_native_bgr" {
                [native[2], native[1], native[0]]
            } else {
                [native[0], native[1], native[2]]
            };
            assert_eq!(light.colour, rgb, "{model}/{case}: light colour");
            assert_eq!(reference["kd"].as_f64(), Some(light.kd));
        }
        let depth = npy::read(dir.join("input_depth.npy.gz")).unwrap();
        assert_eq!(depth.shape, [height as usize, width as usize]);
        let ours = phong
            .render(&depth.data, width as usize, &background)
            .unwrap();
        let (_, _, reference) = png_rgb(dir.join("output.png"));
        assert_matches(&format!("{model}/{case}"), &ours, &reference);
    }
}

#[test]
fn digit_matches_the_reference() {
    check(
        "digit",
        PhongParams {
            texture_sigma: 0.0,
            ..PhongParams::digit()
        },
        "color",
    );
}

#[test]
fn gelsight_matches_the_reference() {
    check(
        "gelsight",
        PhongParams {
            texture_sigma: 0.0,
            ..PhongParams::gelsight2014()
        },
        "color_native_bgr",
    );
}

#[test]
fn geltip_matches_the_reference() {
    use yarok_components::tactile::geltip::{GelTipModel, GelTipParams};
    let (width, height, background) = png_rgb(golden().join("geltip/background.png"));
    let params = GelTipParams::default();
    let mut model = GelTipModel::load(params.clone(), golden().join("geltip/params")).unwrap();
    assert_eq!(model.size(), (width as usize, height as usize));
    for case in cases("geltip") {
        let dir = golden().join("geltip").join(&case);
        let manifest: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).unwrap())
                .unwrap();
        let lights = manifest["parameters"]["light_sources"].as_array().unwrap();
        assert_eq!(params.lights.len(), lights.len(), "geltip/{case}: lights");
        for (light, reference) in params.lights.iter().zip(lights) {
            let bgr: Vec<f64> = reference["color_native_bgr"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            assert_eq!(light.colour, [bgr[2], bgr[1], bgr[0]]);
        }
        let depth = npy::read(dir.join("input_depth.npy.gz")).unwrap();
        let ours = model.render(&depth.data, &background).unwrap();
        let (_, _, reference) = png_rgb(dir.join("output.png"));
        assert_matches(&format!("geltip/{case}"), &ours, &reference);
    }
}
