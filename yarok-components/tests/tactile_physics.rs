//! The optical models make physical sense: deeper presses make larger contacts, an off-centre
//! sphere moves the imprint, outputs have the documented size.

mod common;

use common::{background, depth, golden};
use yarok_components::tactile::geltip::{GelTipModel, GelTipParams};
use yarok_components::tactile::light_fields::{LightFieldMethod, led_ring};
use yarok_components::tactile::npy;
use yarok_components::tactile::phong::{PhongModel, PhongParams};

/// The golden cases kept for `model` (the folders holding an input depth map).
#[cfg(feature = "parallel")]
fn cases(model: &str) -> Vec<String> {
    let mut cases: Vec<String> = std::fs::read_dir(golden(model))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.join("input_depth.npy.gz").exists())
        .map(|path| path.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    cases.sort();
    assert!(cases.len() >= 4, "{model}: {cases:?}");
    cases
}

/// Pixels whose colour differs from the no-contact image by more than 10 levels, and their
/// centroid (column, row).
fn imprint(image: &[u8], untouched: &[u8], width: usize) -> (usize, (f64, f64)) {
    let changed: Vec<usize> = (0..image.len() / 3)
        .filter(|&i| (0..3).any(|c| image[3 * i + c].abs_diff(untouched[3 * i + c]) > 10))
        .collect();
    let n = changed.len().max(1) as f64;
    let centroid = changed.iter().fold((0.0, 0.0), |(u, v), &i| {
        (u + (i % width) as f64 / n, v + (i / width) as f64 / n)
    });
    (changed.len(), centroid)
}

fn check(
    model: &str,
    mut render: impl FnMut(&npy::NpyArray) -> Vec<u8>,
    no_contact: &str,
    offcentre: (f64, f64),
) {
    let untouched = render(&depth(model, no_contact));
    let width = depth(model, no_contact).shape[1];
    let (shallow, centre) = imprint(&render(&depth(model, "sphere_center")), &untouched, width);
    let (deep, _) = imprint(
        &render(&depth(model, "sphere_center_deep")),
        &untouched,
        width,
    );
    let (_, moved) = imprint(
        &render(&depth(model, "sphere_offcenter")),
        &untouched,
        width,
    );
    assert!(
        shallow > 100,
        "{model}: a press leaves an imprint ({shallow} pixels)"
    );
    assert!(
        deep > shallow * 5 / 4,
        "{model}: a deeper press makes a larger contact ({shallow} → {deep} pixels)"
    );
    let height = untouched.len() / 3 / width;
    let middle = ((width as f64 - 1.0) / 2.0, (height as f64 - 1.0) / 2.0);
    assert!(
        (centre.0 - middle.0).abs() < 3.0 && (centre.1 - middle.1).abs() < 3.0,
        "{model}: centred imprint at {centre:?}"
    );
    assert!(
        (moved.0 - offcentre.0).abs() < 6.0 && (moved.1 - offcentre.1).abs() < 6.0,
        "{model}: imprint at {moved:?}, sphere at {offcentre:?}"
    );
}

#[test]
fn digit_imprints_grow_with_depth_and_follow_the_object() {
    let mut model = PhongModel::new(PhongParams {
        texture_sigma: 0.0,
        ..PhongParams::digit()
    });
    let bg = background("digit");
    let image = model
        .render(&depth("digit", "flat_surface").data, 240, &bg)
        .unwrap();
    assert_eq!(
        image.len(),
        320 * 240 * 3,
        "DIGIT: 320 rows × 240 columns, RGB"
    );
    check(
        "digit",
        |d| model.render(&d.data, d.shape[1], &bg).unwrap(),
        "flat_surface",
        (170.0, 95.0),
    );
}

#[test]
fn gelsight_imprints_grow_with_depth_and_follow_the_object() {
    let mut model = PhongModel::new(PhongParams {
        texture_sigma: 0.0,
        ..PhongParams::gelsight2014()
    });
    let bg = background("gelsight");
    check(
        "gelsight",
        |d| model.render(&d.data, d.shape[1], &bg).unwrap(),
        "flat",
        (450.0, 160.0),
    );
}

/// GelTip with the reference's light fields, and with fields the project computes from the
/// membrane's geometry (three LEDs on the base ring, 12.6 mm from the axis at 120°, as the
/// reference's set-up places them) by each method.
#[test]
fn geltip_imprints_grow_with_depth_and_follow_the_object() {
    let membrane = npy::read(golden("geltip/params/bkg_depth_m.npy.gz")).unwrap();
    let (width, params) = (membrane.shape[1], GelTipParams::default());
    let leds = led_ring(3, 0.0126, 0.010);
    let computed = |method| {
        GelTipModel::from_geometry(params.clone(), &membrane.data, width, &leds, method).unwrap()
    };
    let models = [
        GelTipModel::load(params.clone(), golden("geltip/params")).unwrap(),
        computed(LightFieldMethod::Linear),
        computed(LightFieldMethod::Plane),
    ];
    let bg = background("geltip");
    for mut model in models {
        check(
            "geltip",
            |d| model.render(&d.data, &bg).unwrap(),
            "flat",
            (190.0, 95.0),
        );
    }
}

/// GelTip pixels where nothing was measured render as the undeformed membrane by default, so a
/// few of them leave no mark; the reference's behaviour (no fill) leaves one.
#[test]
fn geltip_fills_missing_depth() {
    let membrane = npy::read(golden("geltip/params/bkg_depth_m.npy.gz")).unwrap();
    let bg = background("geltip");
    let pressed = depth("geltip", "sphere_offcenter");
    let mut holes = pressed.data.clone();
    let width = pressed.shape[1];
    let mut filled = pressed.data.clone();
    for (x, y, value) in [(20, 30, 0.0), (160, 120, f32::NAN), (300, 200, -1.0)] {
        holes[y * width + x] = value;
        filled[y * width + x] = membrane.data[y * width + x];
    }
    let mut model = GelTipModel::load(GelTipParams::default(), golden("geltip/params")).unwrap();
    assert_eq!(
        model.render(&holes, &bg).unwrap(),
        model.render(&filled, &bg).unwrap()
    );
    let mut unfilled = GelTipModel::load(
        GelTipParams {
            fill_missing_depth: false,
            ..GelTipParams::default()
        },
        golden("geltip/params"),
    )
    .unwrap();
    assert_ne!(
        unfilled.render(&holes, &bg).unwrap(),
        unfilled.render(&filled, &bg).unwrap()
    );
}

#[test]
fn texture_noise_is_seeded() {
    let bg = background("digit");
    let input = depth("digit", "sphere_center");
    let render = |seed, texture_sigma| {
        PhongModel::new(PhongParams {
            seed,
            texture_sigma,
            ..PhongParams::digit()
        })
        .render(&input.data, 240, &bg)
        .unwrap()
    };
    let first = render(1, 1e-5);
    assert_eq!(first, render(1, 1e-5), "same seed, same bytes");
    assert_ne!(first, render(2, 1e-5), "another seed, another texture");
    assert_ne!(first, render(1, 0.0), "the texture shows");
}

#[test]
fn digit_metric_mode_sees_only_what_presses_into_the_gel() {
    let mut model = PhongModel::new(PhongParams {
        texture_sigma: 0.0,
        ..PhongParams::digit_metric()
    });
    let bg = yarok_components::tactile::default_background(240, 320);
    assert_eq!(bg.len(), 320 * 240 * 3);
    let metric =
        |case: &str| npy::read(golden(&format!("digit/{case}/depth_metric_m.npy.gz"))).unwrap();
    let untouched = model
        .render(&metric("flat_surface").data, 240, &bg)
        .unwrap();
    let (pixels, centre) = imprint(
        &model
            .render(&metric("sphere_center").data, 240, &bg)
            .unwrap(),
        &untouched,
        240,
    );
    assert!(
        pixels > 100 && (centre.0 - 119.5).abs() < 3.0 && (centre.1 - 159.5).abs() < 3.0,
        "{pixels} at {centre:?}"
    );
    let (deeper, _) = imprint(
        &model
            .render(&metric("sphere_center_deep").data, 240, &bg)
            .unwrap(),
        &untouched,
        240,
    );
    assert!(deeper > pixels, "{pixels} → {deeper}");
}

/// Splitting a frame over threads gives the same bytes, noise on, for every golden input (each
/// case is rendered after another, so reused buffers are exercised too).
#[cfg(feature = "parallel")]
#[test]
fn threads_do_not_change_images() {
    for (model, params) in [
        ("digit", PhongParams::digit()),
        ("gelsight", PhongParams::gelsight2014()),
    ] {
        let bg = background(model);
        let (mut single, mut parallel) = (PhongModel::new(params.clone()), PhongModel::new(params));
        parallel.set_parallel(true);
        for case in cases(model) {
            let d = depth(model, &case);
            assert_eq!(
                single.render(&d.data, d.shape[1], &bg).unwrap(),
                parallel.render(&d.data, d.shape[1], &bg).unwrap(),
                "{model}/{case}"
            );
        }
    }
    let load = || GelTipModel::load(GelTipParams::default(), golden("geltip/params")).unwrap();
    let (mut single, mut parallel) = (load(), load());
    parallel.set_parallel(true);
    let bg = background("geltip");
    for case in cases("geltip") {
        let d = depth("geltip", &case);
        assert_eq!(
            single.render(&d.data, &bg).unwrap(),
            parallel.render(&d.data, &bg).unwrap(),
            "geltip/{case}"
        );
    }
}

/// Inputs of the wrong size are errors that name them, and leave the output untouched.
#[test]
fn wrong_sizes_are_errors() {
    use yarok_components::tactile::SizeError;
    let mut phong = PhongModel::new(PhongParams::digit());
    let (depth, background) = (vec![1.0f32; 12], vec![0u8; 36]);
    assert_eq!(
        phong.render(&depth, 5, &background),
        Err(SizeError::NotWholeRows { len: 12, width: 5 })
    );
    assert_eq!(
        phong.render(&depth, 0, &background),
        Err(SizeError::NotWholeRows { len: 12, width: 0 })
    );
    let mut out = vec![7u8; 35];
    let error = phong
        .render_into(&depth, 4, &background, &mut out)
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "the output holds 35 values; a 4 × 3 image needs 36"
    );
    assert!(out.iter().all(|v| *v == 7), "nothing written");
    assert_eq!(phong.render(&[], 4, &[]), Ok(Vec::new()));

    let membrane = vec![0.02f32; 12];
    let params = GelTipParams::default();
    let fields = vec![vec![[0.0, 0.0, 1.0]; 12]; 2];
    assert_eq!(
        GelTipModel::new(params.clone(), &membrane, 4, &fields).unwrap_err(),
        SizeError::LightCount {
            lights: 3,
            fields: 2
        }
    );
    let mut fields = vec![vec![[0.0, 0.0, 1.0]; 12]; 3];
    fields[1].pop();
    assert!(matches!(
        GelTipModel::new(params.clone(), &membrane, 4, &fields),
        Err(SizeError::Mismatch {
            what: "light field",
            actual: 11,
            ..
        })
    ));
    let mut geltip = GelTipModel::new(params, &membrane, 4, &vec![fields[0].clone(); 3]).unwrap();
    assert!(matches!(
        geltip.render(&membrane[..8], &[0; 24]),
        Err(SizeError::Mismatch {
            what: "depth map",
            ..
        })
    ));
}

/// With `clamp_diffuse`, no pixel is darker than the ambient term (`ia` × background); without
/// it, as in the reference, surfaces facing away from a light are.
#[test]
fn clamped_diffuse_never_darkens_below_the_ambient_term() {
    let bg = background("geltip");
    let pressed = depth("geltip", "sphere_offcenter");
    let darkest_below_ambient = |clamp_diffuse: bool| {
        let params = GelTipParams {
            clamp_diffuse,
            ..GelTipParams::default()
        };
        let ambient = params.ia;
        let mut model = GelTipModel::load(params, golden("geltip/params")).unwrap();
        let image = model.render(&pressed.data, &bg).unwrap();
        image
            .iter()
            .zip(&bg)
            .map(|(out, back)| ambient * f64::from(*back) - f64::from(*out))
            .fold(f64::MIN, f64::max)
    };
    let clamped = darkest_below_ambient(true);
    assert!(
        clamped <= 1.0,
        "a pixel is {clamped:.1} levels below the ambient term"
    );
    let unclamped = darkest_below_ambient(false);
    assert!(
        unclamped > 5.0,
        "the reference's dark crescents: {unclamped:.1}"
    );
}
