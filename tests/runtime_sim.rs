//! Behaviours in simulation: deterministic, in simulated time, with the same code in `mock`.

use std::cell::RefCell;
use std::rc::Rc;

use yarok::components::cameras::Cam;
use yarok::components::robots::AnetA30;
use yarok::components::worlds::PrinterWorld;
use yarok_test::assert_says;

/// Moves the printer through a few poses, recording where the head is on every tick.
fn trajectory(environment: &str) -> Vec<[f64; 3]> {
    let samples = Rc::new(RefCell::new(Vec::new()));
    let log = Rc::clone(&samples);
    yarok::platform()
        .world::<PrinterWorld>()
        .environment(environment)
        .behaviour(move |pl| async move {
            let printer: AnetA30 = pl.get("/printer")?;
            for pose in [
                [50.0, 80.0, 300.0],
                [250.0, 200.0, 100.0],
                [0.0, 320.0, 420.0],
            ] {
                let target = printer.move_to(pose);
                pl.wait(|| printer.is_at(target))
                    .on_tick(|| log.borrow_mut().push(printer.at()))
                    .timeout(10.0)
                    .await?;
            }
            Ok(())
        })
        .run()
        .unwrap();
    samples.take()
}

#[test]
fn the_same_run_twice_gives_bit_identical_trajectories() {
    let (first, second) = (trajectory("sim"), trajectory("sim"));
    assert!(
        first.len() > 100,
        "the head takes time to move: {} ticks",
        first.len()
    );
    assert_eq!(first, second);
}

#[test]
fn the_same_behaviour_runs_in_the_mock_environment() {
    let mock = trajectory("mock");
    assert_eq!(
        mock,
        [
            [50.0, 80.0, 300.0],
            [250.0, 200.0, 100.0],
            [0.0, 320.0, 420.0]
        ],
        "mock moves in one tick"
    );
}

#[test]
fn wait_seconds_is_simulated_time_to_within_one_step() {
    yarok::platform()
        .world::<PrinterWorld>()
        .behaviour(|pl| async move {
            let start = pl.time();
            pl.wait_seconds(1.0).await?;
            let elapsed = pl.time() - start;
            assert!(
                (elapsed - 1.0).abs() <= pl.timestep() / 2.0 + 1e-12,
                "{elapsed}"
            );
            assert_eq!(pl.ticks(), (1.0 / pl.timestep()).round() as u64);
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn the_camera_rides_on_the_printer_head() {
    yarok::platform()
        .world::<PrinterWorld>()
        .behaviour(|pl| async move {
            let printer: AnetA30 = pl.get("printer")?;
            let camera: Cam = pl.get("/printer/cam")?;
            let target = printer.move_to([160.0, 160.0, 420.0]);
            pl.wait(|| printer.is_at(target)).timeout(10.0).await?;
            let above_tower = camera.read_depth()?;
            let centre = above_tower.get_pixel(160, 120)[0];
            // The head is 0.42 m up; the 4-layer tower's top is at about 0.24 m.
            assert!(
                (centre - 0.18).abs() < 0.02,
                "tower top {centre} m below the camera"
            );
            let target = printer.move_to([320.0, 0.0, 420.0]);
            pl.wait(|| printer.is_at(target)).timeout(10.0).await?;
            let beside = camera.read_depth()?.get_pixel(160, 120)[0];
            assert!(
                (beside - 0.42).abs() < 0.02,
                "floor {beside} m below the camera"
            );
            assert_eq!(camera.read()?.dimensions(), (320, 240));
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn a_fast_camera_gives_colour_and_depth_of_one_instant_from_one_draw() {
    yarok::platform()
        .world::<PrinterWorld>()
        .set("/printer/cam/preset=\"fast\"")
        .unwrap()
        .behaviour(|pl| async move {
            let printer: AnetA30 = pl.get("printer")?;
            let camera: Cam = pl.get("/printer/cam")?;
            let target = printer.move_to([160.0, 160.0, 420.0]);
            pl.wait(|| printer.is_at(target)).timeout(10.0).await?;
            let (rgb, depth) = camera.read_rgbd()?;
            assert!(
                rgb == camera.read()?,
                "the colour differs from a colour-only draw"
            );
            let alone = camera.read_depth()?;
            let centre = depth.get_pixel(160, 120)[0];
            assert!((centre - 0.18).abs() < 0.02, "tower top {centre} m below");
            assert_eq!(alone.get_pixel(160, 120), depth.get_pixel(160, 120));
            Ok(())
        })
        .run()
        .unwrap();
    let error = yarok::platform()
        .world::<PrinterWorld>()
        .set("/printer/cam/preset=\"pretty\"")
        .unwrap()
        .behaviour(|_| async { Ok(()) })
        .run()
        .unwrap_err()
        .to_string();
    assert_says(&error, &["/printer/cam", "\"pretty\""]);
}
