//! The hardware backend ticks at its rate on tokio's clock, so paused-time tests are instant.

use std::cell::Cell;
use std::rc::Rc;

use yarok_core::component::{Component, Declaration};
use yarok_core::runtime::{Platform, RuntimeError, World};
use yarok_hw::{HardwareBackend, InvalidTickRate, Real};

struct Bench;
impl Component for Bench {
    fn declaration() -> Declaration {
        Declaration::new("bench").template("<mujoco><worldbody/></mujoco>")
    }
}

#[tokio::test(start_paused = true)]
async fn ten_seconds_at_100_hz_are_exactly_1000_ticks_and_take_no_wall_time() {
    let ticks = Rc::new(Cell::new(0u64));
    let counted = Rc::clone(&ticks);
    let started = tokio::time::Instant::now();
    let platform = Platform::builder()
        .world::<Bench>()
        .environment("real")
        .set("platform/tick_hz=100")
        .unwrap()
        .backend::<Real>(HardwareBackend::from_settings)
        .plugin(move |_: &World<'_>| {
            counted.set(counted.get() + 1);
            Ok(())
        })
        .behaviour(|pl| async move {
            pl.wait_seconds(10.0).await?;
            assert!(
                (pl.time() - 10.0).abs() < 1e-6,
                "platform time {}",
                pl.time()
            );
            Ok(())
        })
        .build()
        .unwrap();
    tokio::task::LocalSet::new()
        .run_until(platform.run_local())
        .await
        .unwrap();
    assert_eq!(ticks.get(), 1000);
    assert_eq!(
        started.elapsed(),
        std::time::Duration::from_secs(10),
        "virtual time, not wall time"
    );
}

#[test]
fn a_bad_rate_is_refused() {
    let error = Platform::builder()
        .world::<Bench>()
        .environment("real")
        .set("platform/tick_hz=0")
        .unwrap()
        .backend::<Real>(HardwareBackend::from_settings)
        .build()
        .unwrap_err();
    assert!(
        matches!(
            &error,
            RuntimeError::Backend { source, .. } if source.downcast_ref::<InvalidTickRate>() == Some(&InvalidTickRate(0.0))
        ),
        "{error}"
    );
    assert!(
        error
            .to_string()
            .contains("tick_hz must be a positive rate"),
        "{error}"
    );
}
