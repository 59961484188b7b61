//! The pan-tilt mount centres the red block in its camera's image, in `sim` (MuJoCo turns the
//! links) and in `mock` (the links are set where they are told, the camera renders the world as
//! declared): the same vision behaviour, two drives.

use std::cell::Cell;
use std::rc::Rc;

use my_turntable::pan_tilt::{Lookout, PanTilt, centre_on_red};

/// Centres the block in `environment`; the pixel offset left and where the mount turned.
fn centre(environment: &str) -> ((f64, f64), (f64, f64)) {
    let seen = Rc::new(Cell::new(((f64::NAN, f64::NAN), (f64::NAN, f64::NAN))));
    let keep = Rc::clone(&seen);
    yarok::platform()
        .world::<Lookout>()
        .args(["--env".to_owned(), environment.to_owned()])
        .unwrap()
        .behaviour(move |pl| async move {
            let offset = centre_on_red(pl.clone()).await?;
            let mount: PanTilt = pl.get("/mount")?;
            keep.set((offset, mount.angles()));
            Ok(())
        })
        .run()
        .unwrap();
    seen.get()
}

#[test]
fn the_mount_centres_the_red_block_in_sim_and_in_mock() {
    // The block is 0.8 m ahead of the mount, 0.2 m to the left and 0.17 m below the camera.
    let expected_pan = 0.2f64.atan2(0.8);
    for environment in ["sim", "mock"] {
        let ((dx, dy), (pan, tilt)) = centre(environment);
        println!("{environment}: offset ({dx:.2}, {dy:.2}) px, pan {pan:.3}, tilt {tilt:.3}");
        assert!(
            dx.abs() < 1.5 && dy.abs() < 1.5,
            "{environment}: ({dx}, {dy})"
        );
        assert!(
            (pan - expected_pan).abs() < 0.05,
            "{environment}: pan {pan}"
        );
        assert!(
            tilt > 0.1,
            "{environment}: it looks down at the block: {tilt}"
        );
    }
}
