//! Headless rendering of a known scene: depth in metres, colours, orientation, sizes.
#![cfg(feature = "render")]

use std::sync::Arc;

use yarok_mjc::{Data, Model, RenderError, RenderPreset, Renderer};

/// A camera 2 m above a green floor looking straight down (image up = world +y, image right =
/// world +x). Only a full-ambient headlight lights the scene, so colours come out exactly.
const SCENE: &str = r#"
<mujoco>
  <visual>
    <global offwidth="400" offheight="300"/>
    <headlight ambient="1 1 1" diffuse="0 0 0" specular="0 0 0"/>
  </visual>
  <worldbody>
    <camera name="down" pos="0 0 2"/>
    <geom type="plane" size="3 3 0.1" rgba="0 1 0 1"/>
    <geom name="north" type="box" pos="0 0.5 0.05" size="0.05 0.05 0.05" rgba="1 0 0 1"/>
    <geom name="east" type="box" pos="0.5 0 0.05" size="0.05 0.05 0.05" rgba="0 0 1 1"/>
  </worldbody>
</mujoco>"#;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;

fn scene() -> (Arc<Model>, Data) {
    let model = Arc::new(Model::from_xml_str(SCENE).unwrap());
    let mut data = Data::new(&model).unwrap();
    data.forward();
    (model, data)
}

fn pixels_of(rgb: &image::RgbImage, colour: [u8; 3]) -> Vec<(u32, u32)> {
    rgb.enumerate_pixels()
        .filter(|(_, _, p)| p.0 == colour)
        .map(|(x, y, _)| (x, y))
        .collect()
}

#[test]
fn depth_colour_and_orientation_of_a_known_scene() {
    let (model, mut data) = scene();
    for preset in [
        RenderPreset::Quality,
        RenderPreset::Fast,
        RenderPreset::Depth,
    ] {
        let mut renderer = Renderer::builder()
            .size(WIDTH, HEIGHT)
            .preset(preset)
            .build(&model)
            .unwrap();
        let (rgb, depth) = renderer
            .render(&mut data, model.camera("down").unwrap())
            .unwrap();
        assert_eq!(rgb.dimensions(), (WIDTH, HEIGHT));
        assert_eq!(depth.dimensions(), (WIDTH, HEIGHT));

        let centre = depth.get_pixel(WIDTH / 2, HEIGHT / 2)[0];
        assert!(
            (centre - 2.0).abs() < 1e-3,
            "{preset:?}: floor depth {centre} m, expected 2 m"
        );
        assert_eq!(
            rgb.get_pixel(WIDTH / 2, HEIGHT / 2).0,
            [0, 255, 0],
            "{preset:?}: floor colour"
        );

        let north = pixels_of(&rgb, [255, 0, 0]);
        assert!(!north.is_empty(), "{preset:?}: the +y box is visible");
        assert!(
            north.iter().all(|&(_, y)| y < HEIGHT / 3),
            "{preset:?}: +y box in the top rows"
        );
        let (x, y) = north[north.len() / 2];
        let top = depth.get_pixel(x, y)[0];
        assert!(
            (top - 1.9).abs() < 1e-3,
            "{preset:?}: box top at {top} m, expected 1.9 m"
        );

        let east = pixels_of(&rgb, [0, 0, 255]);
        assert!(!east.is_empty(), "{preset:?}: the +x box is visible");
        assert!(
            east.iter().all(|&(x, _)| x > 2 * WIDTH / 3),
            "{preset:?}: +x box on the right"
        );
    }
}

#[test]
fn rgb_and_depth_alone_match_the_combined_render() {
    let (model, mut data) = scene();
    let camera = model.camera("down").unwrap();
    let mut renderer = Renderer::builder()
        .size(WIDTH, HEIGHT)
        .preset(RenderPreset::Fast)
        .build(&model)
        .unwrap();
    let (rgb, depth) = renderer.render(&mut data, camera).unwrap();
    assert_eq!(renderer.render_rgb(&mut data, camera).unwrap(), rgb);
    let alone = renderer.render_depth(&mut data, camera).unwrap();
    let differing: Vec<_> = alone
        .enumerate_pixels()
        .filter(|(x, y, d)| d[0] != depth.get_pixel(*x, *y)[0])
        .map(|(x, y, d)| (x, y, d[0], depth.get_pixel(x, y)[0]))
        .collect();
    assert!(
        differing.is_empty(),
        "{} pixels differ, e.g. {:?}",
        differing.len(),
        &differing[..differing.len().min(5)]
    );
}

#[test]
fn images_larger_than_the_models_offscreen_buffer_render_and_empty_ones_are_refused() {
    let (model, mut data) = scene();
    let camera = model.camera("down").unwrap();
    // The model asks for a 400x300 offscreen buffer; each renderer makes its own.
    let mut renderer = Renderer::builder()
        .size(640, 480)
        .preset(RenderPreset::Fast)
        .build(&model)
        .unwrap();
    let depth = renderer.render_depth(&mut data, camera).unwrap();
    assert_eq!(depth.dimensions(), (640, 480));
    assert!((depth.get_pixel(320, 240)[0] - 2.0).abs() < 1e-3);
    let error = Renderer::builder().size(0, 10).build(&model).unwrap_err();
    assert_eq!(
        error,
        RenderError::Empty {
            width: 0,
            height: 10
        }
    );
    assert!(Renderer::builder().size(400, 300).build(&model).is_ok());
}

#[test]
fn data_or_camera_of_another_model_is_refused() {
    let (model, mut data) = scene();
    let other = Arc::new(
        Model::from_xml_str(r#"<mujoco><worldbody><camera name="c"/></worldbody></mujoco>"#)
            .unwrap(),
    );
    let mut other_data = Data::new(&other).unwrap();
    let mut renderer = Renderer::builder().size(32, 24).build(&model).unwrap();
    let camera = model.camera("down").unwrap();
    assert_eq!(
        renderer.render_rgb(&mut other_data, camera),
        Err(RenderError::ModelMismatch)
    );
    let foreign_camera = other.camera("c").unwrap();
    assert_eq!(
        renderer.render_rgb(&mut data, foreign_camera),
        Err(RenderError::ModelMismatch)
    );
}

#[test]
fn renderers_sharing_a_thread_keep_their_own_buffers_and_images() {
    let (model, mut data) = scene();
    let camera = model.camera("down").unwrap();
    let mut small = Renderer::builder()
        .size(64, 48)
        .preset(RenderPreset::Fast)
        .build(&model)
        .unwrap();
    let mut large = Renderer::builder()
        .size(WIDTH, HEIGHT)
        .preset(RenderPreset::Fast)
        .build(&model)
        .unwrap();
    let first = small.render_rgb(&mut data, camera).unwrap();
    let large_first = large.render(&mut data, camera).unwrap();
    assert_eq!(small.render_rgb(&mut data, camera).unwrap(), first);
    // A renderer made while the others live, on the thread's one OpenGL context.
    let mut quality = Renderer::builder()
        .size(WIDTH, HEIGHT)
        .preset(RenderPreset::Quality)
        .build(&model)
        .unwrap();
    quality.render_rgb(&mut data, camera).unwrap();
    assert!(large.render(&mut data, camera).unwrap() == large_first);
    drop(large);
    assert_eq!(small.render_rgb(&mut data, camera).unwrap(), first);
    drop(small);
    assert_eq!(
        quality.render_rgb(&mut data, camera).unwrap().dimensions(),
        (WIDTH, HEIGHT)
    );
}

#[test]
fn renderers_work_on_several_threads_at_once() {
    let handles: Vec<_> = (0..2)
        .map(|_| {
            std::thread::spawn(|| {
                let (model, mut data) = scene();
                let mut renderer = Renderer::builder().size(64, 48).build(&model).unwrap();
                renderer
                    .render_depth(&mut data, model.camera("down").unwrap())
                    .unwrap()
                    .get_pixel(32, 24)[0]
            })
        })
        .collect();
    for handle in handles {
        assert!((handle.join().unwrap() - 2.0).abs() < 1e-3);
    }
}

/// Renderers made, used and dropped on several threads at once, over and over, while this
/// thread does the same: every image is right and the process survives.
#[test]
fn renderers_made_and_dropped_on_many_threads_at_once() {
    let churn = || {
        let (model, mut data) = scene();
        let camera = model.camera("down").unwrap();
        for round in 0..12 {
            let preset = if round % 2 == 0 {
                RenderPreset::Fast
            } else {
                RenderPreset::Quality
            };
            let mut renderer = Renderer::builder()
                .size(32 + round, 24)
                .preset(preset)
                .build(&model)
                .unwrap();
            let depth = renderer.render_depth(&mut data, camera).unwrap();
            let centre = depth.get_pixel(depth.width() / 2, 12)[0];
            assert!((centre - 2.0).abs() < 1e-3, "round {round}: {centre}");
        }
    };
    let threads: Vec<_> = (0..4).map(|_| std::thread::spawn(churn)).collect();
    churn();
    for thread in threads {
        thread.join().unwrap();
    }
}

/// An offscreen buffer or multisampling beyond what OpenGL supports is an error, not MuJoCo's
/// fatal "framebuffer is not complete" abort; so is a scene too large to allocate.
#[test]
fn buffers_beyond_the_gl_limits_are_refused() {
    for (visual, (width, height)) in [
        ("", (1_000_000, 64)),
        ("", (64, 1_000_000)),
        (r#"<quality offsamples="1000"/>"#, (32, 32)),
        // Within the size and sample limits, but past llvmpipe's 1 GiB a buffer (MuJoCo
        // would abort the process on the incomplete framebuffer).
        ("", (8200, 8200)),
        ("", (16384, 16384)),
    ] {
        let model = Arc::new(
            Model::from_xml_str(&format!(
                r#"<mujoco><visual>{visual}</visual><worldbody><camera name="c"/></worldbody></mujoco>"#
            ))
            .unwrap(),
        );
        let error = Renderer::builder()
            .size(width, height)
            .preset(RenderPreset::Quality)
            .build(&model)
            .unwrap_err();
        assert!(
            matches!(error, RenderError::BeyondGl { max_width, max_height, .. }
                if max_width >= 1024 && max_height >= 1024),
            "{visual} {width}x{height}: {error:?}"
        );
        assert!(error.to_string().contains("offsamples"), "{error}");
    }
    let (model, _) = scene();
    let error = Renderer::builder()
        .size(32, 32)
        .max_geoms(yarok_mjc::MAX_GEOMS + 1)
        .build(&model)
        .unwrap_err();
    assert!(
        matches!(error, RenderError::TooManyGeoms { .. }),
        "{error:?}"
    );
}

#[test]
fn a_reach_draws_only_what_comes_near_the_camera() {
    let (model, mut data) = scene();
    let camera = model.camera("down").unwrap();
    let mut renderer = Renderer::builder()
        .size(WIDTH, HEIGHT)
        .preset(RenderPreset::Fast)
        .build(&model)
        .unwrap();
    let everything = renderer.render_depth(&mut data, camera).unwrap();
    // The boxes' tops are 1.9 m from the camera, the floor 2 m.
    renderer.set_reach(Some(1.95));
    let mut near = yarok_mjc::DepthImage::new(1, 1);
    renderer
        .render_depth_into(&mut data, camera, &mut near)
        .unwrap();
    assert_eq!(near.dimensions(), (WIDTH, HEIGHT));
    let (floor_x, floor_y) = (WIDTH / 2, HEIGHT / 2);
    assert!((everything.get_pixel(floor_x, floor_y)[0] - 2.0).abs() < 1e-3);
    assert!(
        near.get_pixel(floor_x, floor_y)[0] > 10.0,
        "the floor is beyond reach: {}",
        near.get_pixel(floor_x, floor_y)[0]
    );
    let box_pixels: Vec<_> = everything
        .enumerate_pixels()
        .filter(|(_, _, depth)| (depth[0] - 1.9).abs() < 1e-3)
        .map(|(x, y, _)| (x, y))
        .collect();
    assert!(!box_pixels.is_empty());
    for &(x, y) in &box_pixels {
        assert_eq!(
            near.get_pixel(x, y),
            everything.get_pixel(x, y),
            "box at ({x}, {y})"
        );
    }
    renderer.set_reach(None);
    assert_eq!(
        renderer.render_depth(&mut data, camera).unwrap(),
        everything
    );
}

#[test]
fn depth_alone_skips_the_skybox_that_colour_draws() {
    let model = Arc::new(
        Model::from_xml_str(
            r#"<mujoco>
              <visual><global offwidth="320" offheight="240"/><map zfar="50"/></visual>
              <statistic extent="1"/>
              <asset><texture type="skybox" builtin="gradient" rgb1="1 1 1" rgb2="0 0 1"
                              width="64" height="64"/></asset>
              <worldbody>
                <camera name="horizon" pos="0 0 1" xyaxes="1 0 0 0 0 1"/>
                <geom type="plane" size="5 5 0.1" rgba="0 1 0 1"/>
              </worldbody>
            </mujoco>"#,
        )
        .unwrap(),
    );
    let mut data = Data::new(&model).unwrap();
    data.forward();
    let camera = model.camera("horizon").unwrap();
    let mut renderer = Renderer::builder()
        .size(WIDTH, HEIGHT)
        .preset(RenderPreset::Fast)
        .build(&model)
        .unwrap();
    let (rgb, depth) = renderer.render(&mut data, camera).unwrap();
    let alone = renderer.render_depth(&mut data, camera).unwrap();
    let (mut floor, mut sky) = (0, 0);
    for (x, y, colour) in rgb.enumerate_pixels() {
        let (combined, alone) = (depth.get_pixel(x, y)[0], alone.get_pixel(x, y)[0]);
        // Looking level from 1 m up: the floor below the horizon, the sky above.
        if y > 3 * HEIGHT / 4 {
            floor += 1;
            assert_eq!(alone, combined, "the floor at ({x}, {y})");
        } else if y < HEIGHT / 4 {
            sky += 1;
            assert!(
                colour.0[2] > 100,
                "the sky is drawn at ({x}, {y}): {colour:?}"
            );
            assert!(
                (alone - 50.0).abs() < 1e-3,
                "no depth at ({x}, {y}): {alone}"
            );
        }
    }
    assert!(
        floor > 1000 && sky > 1000,
        "{floor} floor and {sky} sky pixels"
    );
}

#[test]
fn the_depth_preset_sees_the_same_depth_without_textures() {
    let model = Arc::new(
        Model::from_xml_str(
            r#"<mujoco>
              <asset>
                <texture name="sky" type="skybox" builtin="gradient" rgb1="1 1 1" rgb2="0 0 1"
                         width="64" height="64"/>
                <texture name="checker" type="2d" builtin="checker" rgb1="1 1 1" rgb2="0 0 0"
                         width="64" height="64"/>
                <material name="checker" texture="checker" texrepeat="8 8"/>
              </asset>
              <worldbody>
                <camera name="down" pos="0 0 2"/>
                <geom type="plane" size="3 3 0.1" material="checker"/>
                <geom type="box" pos="0.3 0.2 0.1" size="0.1 0.1 0.1" material="checker"/>
              </worldbody>
            </mujoco>"#,
        )
        .unwrap(),
    );
    let mut data = Data::new(&model).unwrap();
    data.forward();
    let camera = model.camera("down").unwrap();
    let build = |preset| {
        Renderer::builder()
            .size(WIDTH, HEIGHT)
            .preset(preset)
            .build(&model)
            .unwrap()
    };
    let (fast_rgb, fast_depth) = build(RenderPreset::Fast).render(&mut data, camera).unwrap();
    let (depth_rgb, depth) = build(RenderPreset::Depth)
        .render(&mut data, camera)
        .unwrap();
    assert!(depth == fast_depth, "the depth differs");
    let colours = |rgb: &image::RgbImage| {
        let mut seen: Vec<[u8; 3]> = rgb.pixels().map(|p| p.0).collect();
        seen.sort_unstable();
        seen.dedup();
        seen.len()
    };
    // The checker shows in the fast preset's colours; untextured, the floor is one shade.
    assert!(
        colours(&fast_rgb) > 2 * colours(&depth_rgb),
        "{} vs {}",
        colours(&fast_rgb),
        colours(&depth_rgb)
    );
}
