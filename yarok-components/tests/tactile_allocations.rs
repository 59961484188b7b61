//! "A frame allocates nothing": once a model has rendered one frame of a size, rendering more
//! frames into a caller's buffer allocates no memory, counted on the rendering thread by
//! `allocation-counter`'s global allocator.

mod common;

use common::{background, depth, golden};
use yarok_components::tactile::calibration::{Calibration, RenderBuffers, ball_press};
use yarok_components::tactile::geltip::{GelTipModel, GelTipParams};
use yarok_components::tactile::phong::{PhongModel, PhongParams};

/// Allocations `frame` makes on this thread.
fn allocations(frame: impl FnOnce()) -> u64 {
    allocation_counter::measure(frame).count_total
}

#[test]
fn phong_frames_allocate_nothing() {
    for (model, params) in [
        ("digit", PhongParams::digit()),
        ("gelsight", PhongParams::gelsight2014()),
    ] {
        let bg = background(model);
        let depth = depth(model, "sphere_center");
        let width = depth.shape[1];
        let mut phong = PhongModel::new(params);
        let mut out = vec![0; bg.len()];
        phong
            .render_into(&depth.data, width, &bg, &mut out)
            .unwrap();
        let counted = allocations(|| {
            for _ in 0..3 {
                phong
                    .render_into(&depth.data, width, &bg, &mut out)
                    .unwrap();
            }
        });
        assert_eq!(counted, 0, "{model}");
        assert!(out.iter().any(|&v| v != 0), "{model}: a frame was drawn");
        assert!(
            allocations(|| drop(phong.render(&depth.data, width, &bg).unwrap())) > 0,
            "the counter counts"
        );
    }
}

#[test]
fn geltip_frames_allocate_nothing() {
    let bg = background("geltip");
    let depth = depth("geltip", "sphere_center");
    let mut model = GelTipModel::load(GelTipParams::default(), golden("geltip/params")).unwrap();
    let mut out = vec![0; bg.len()];
    model.render_into(&depth.data, &bg, &mut out).unwrap();
    let counted = allocations(|| {
        for _ in 0..3 {
            model.render_into(&depth.data, &bg, &mut out).unwrap();
        }
    });
    assert_eq!(counted, 0);
    assert!(out.iter().any(|&v| v != 0));
}

#[test]
fn calibrated_frames_allocate_nothing() {
    let digit = Calibration::digit();
    let (width, height) = digit.size();
    let metres_per_pixel = 5e-5;
    let indentation: Vec<f32> = ball_press(width, height, [120.0, 160.0], 30.0, 46.0)
        .iter()
        .map(|pixels| (pixels * metres_per_pixel) as f32)
        .collect();
    let mut buffers = RenderBuffers::default();
    let mut out = vec![0; width * height * 3];
    digit
        .render_indentation_into(&indentation, metres_per_pixel, &mut buffers, &mut out)
        .unwrap();
    let counted = allocations(|| {
        for _ in 0..3 {
            digit
                .render_indentation_into(&indentation, metres_per_pixel, &mut buffers, &mut out)
                .unwrap();
        }
    });
    assert_eq!(counted, 0);
    assert_ne!(out, digit.background().as_raw()[..], "a press was drawn");
    assert_eq!(
        out,
        digit
            .render_indentation(&indentation, metres_per_pixel)
            .unwrap()
            .into_raw(),
        "the same image as a frame rendered afresh"
    );
}
