//! Waits resolve on ticks, in platform time; timeouts end waits that would never resolve.

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use yarok_core::component::{Component, Declaration, Mock, MockBackend};
use yarok_core::runtime::{Platform, PlatformBuilder, RuntimeError};
use yarok_core::time::WaitError;

struct Empty;
impl Component for Empty {
    fn declaration() -> Declaration {
        Declaration::new("empty").template("<mujoco><worldbody/></mujoco>")
    }
}

/// A platform on a mock backend of 10 ms ticks.
fn platform() -> PlatformBuilder {
    Platform::builder()
        .world::<Empty>()
        .environment("mock")
        .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
}

#[test]
fn wait_resolves_on_the_first_tick_after_which_the_condition_holds() {
    platform()
        .behaviour(|pl| async move {
            pl.wait(|| true).await?;
            assert_eq!(pl.ticks(), 1, "at least one tick passes");
            let start = pl.ticks();
            let probe = pl.clone();
            pl.wait(move || probe.ticks() >= start + 5).await?;
            assert_eq!(pl.ticks(), start + 5);
            pl.tick().await?;
            assert_eq!(pl.ticks(), start + 6);
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn wait_seconds_counts_platform_time_to_the_tick() {
    platform()
        .behaviour(|pl| async move {
            pl.wait_seconds(1.0).await?;
            assert_eq!(pl.ticks(), 100);
            assert!((pl.time() - 1.0).abs() < 1e-9);
            pl.wait_seconds(0.004).await?;
            assert_eq!(
                pl.ticks(),
                101,
                "less than half a tick, but a wait always takes a tick"
            );
            pl.wait_seconds(0.016).await?;
            assert_eq!(pl.ticks(), 103, "rounded to the nearest tick");
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn timeouts_end_waits_that_never_resolve() {
    platform()
        .behaviour(|pl| async move {
            let line = line!() + 1;
            let result = pl.wait(|| false).timeout(0.5).await;
            let Err(WaitError::Timeout { seconds, location }) = result else {
                panic!("{result:?}");
            };
            assert_eq!(seconds, 0.5);
            assert_eq!((location.file(), location.line()), (file!(), line));
            assert_eq!(
                result.unwrap_err().to_string(),
                format!(
                    "the wait made at {}:{line}:29 timed out after 0.5 s of platform time",
                    file!()
                )
            );
            assert_eq!(pl.ticks(), 50);
            let result = pl.wait_forever().timeout(0.25).await;
            assert!(matches!(
                result,
                Err(WaitError::Timeout { seconds: 0.25, .. })
            ));
            assert_eq!(pl.ticks(), 75);
            Ok(())
        })
        .run()
        .unwrap();
}

#[test]
fn per_tick_callbacks_see_every_tick_of_the_wait() {
    let seen = Rc::new(RefCell::new(Vec::new()));
    let log = Rc::clone(&seen);
    platform()
        .behaviour(move |pl| async move {
            let clock = pl.clone();
            pl.wait_seconds(0.05)
                .on_tick(|| log.borrow_mut().push(clock.ticks()))
                .await?;
            Ok(())
        })
        .run()
        .unwrap();
    assert_eq!(*seen.borrow(), [1, 2, 3, 4, 5]);
}

#[test]
fn behaviours_run_concurrently_and_share_ticks() {
    let events = Rc::new(RefCell::new(Vec::new()));
    let (a, b) = (Rc::clone(&events), Rc::clone(&events));
    platform()
        .behaviour(move |pl| async move {
            for _ in 0..3 {
                pl.wait_seconds(0.02).await?;
                a.borrow_mut().push(("a", pl.ticks()));
            }
            Ok(())
        })
        .behaviour(move |pl| async move {
            for _ in 0..2 {
                pl.wait_seconds(0.03).await?;
                b.borrow_mut().push(("b", pl.ticks()));
            }
            Ok(())
        })
        .run()
        .unwrap();
    assert_eq!(
        *events.borrow(),
        [("a", 2), ("b", 3), ("a", 4), ("a", 6), ("b", 6)]
    );
}

#[test]
fn a_behaviour_error_reaches_the_caller_and_stops_the_others() {
    let other_ticks = Rc::new(Cell::new(0));
    let counter = Rc::clone(&other_ticks);
    let error = platform()
        .behaviour(move |pl| async move {
            loop {
                pl.tick().await?;
                counter.set(pl.ticks());
            }
        })
        .behaviour(|pl| async move {
            pl.wait_seconds(0.1).await?;
            Err("gripper jammed".into())
        })
        .run()
        .unwrap_err();
    assert!(
        matches!(&error, RuntimeError::Behaviour { index: 1, source, .. } if source.to_string() == "gripper jammed"),
        "{error}"
    );
    assert_eq!(
        error.to_string(),
        format!(
            "behaviour closure at {}:{}:10 failed: gripper jammed",
            file!(),
            line!() - 15
        )
    );
    assert_eq!(other_ticks.get(), 10);
}

async fn pick_and_place(pl: yarok_core::runtime::Pl) -> yarok_core::runtime::BehaviourResult {
    pl.wait(|| false).timeout(0.05).await?;
    Ok(())
}

/// A failed behaviour is named by its function or its label, and a timed-out wait by where it
/// was made.
#[test]
fn failed_behaviours_are_named() {
    let error = platform().behaviour(pick_and_place).run().unwrap_err();
    let message = error.to_string();
    assert!(
        message.starts_with(&format!(
            "behaviour pick_and_place failed: the wait made at {}:",
            file!()
        )),
        "{message}"
    );
    let error = platform()
        .behaviour_named("left arm", pick_and_place)
        .run()
        .unwrap_err();
    assert!(
        error.to_string().starts_with("behaviour left arm failed"),
        "{error}"
    );
}

#[test]
fn stop_ends_the_run_and_pending_waits_report_it() {
    let reported = Rc::new(Cell::new(false));
    let flag = Rc::clone(&reported);
    platform()
        .behaviour(|pl| async move {
            pl.wait_seconds(0.1).await?;
            pl.stop();
            Ok(())
        })
        .behaviour(move |pl| async move {
            assert_eq!(pl.wait_forever().await, Err(WaitError::Stopped));
            flag.set(true);
            Ok(())
        })
        .run()
        .unwrap();
    assert!(reported.get(), "the waiting behaviour saw the stop");
}

#[tokio::test(start_paused = true)]
async fn realtime_pacing_follows_simulated_time_on_tokios_clock() {
    let started = tokio::time::Instant::now();
    let platform = platform()
        .set("platform/realtime=true")
        .unwrap()
        .behaviour(|pl| async move {
            pl.wait_seconds(2.0).await?;
            Ok(())
        })
        .build()
        .unwrap();
    tokio::task::LocalSet::new()
        .run_until(platform.run_local())
        .await
        .unwrap();
    assert_eq!(started.elapsed(), std::time::Duration::from_secs(2));
}

/// NaN and negative durations are errors at once (they used to wait forever or never time out);
/// infinity means forever.
#[test]
fn nan_and_negative_durations_are_errors() {
    platform()
        .behaviour(|pl| async move {
            for seconds in [f64::NAN, -1.0, f64::NEG_INFINITY] {
                let line = line!() + 1;
                let result = pl.wait_seconds(seconds).await;
                let Err(WaitError::InvalidDuration { what, location, .. }) = result else {
                    panic!("wait_seconds({seconds}): {result:?}");
                };
                assert_eq!((what, location.line()), ("wait_seconds", line));
                let result = pl.wait_forever().timeout(seconds).await;
                assert!(
                    matches!(
                        result,
                        Err(WaitError::InvalidDuration {
                            what: "timeout",
                            ..
                        })
                    ),
                    "timeout({seconds}): {result:?}"
                );
            }
            assert_eq!(pl.ticks(), 0, "invalid waits end without a tick");
            let message = pl.wait_seconds(f64::NAN).await.unwrap_err().to_string();
            assert!(message.starts_with("wait_seconds(NaN) at "), "{message}");
            let result = pl.wait_forever().timeout(f64::INFINITY).timeout(0.1).await;
            assert!(
                matches!(result, Err(WaitError::Timeout { .. })),
                "{result:?}"
            );
            Ok(())
        })
        .run()
        .unwrap();
}

/// `pl.timeout` bounds any future in platform time: under tokio's paused clock a paced platform
/// runs hours of platform time instantly, and the deadline is counted in ticks, not wall time.
#[tokio::test(start_paused = true)]
async fn pl_timeout_bounds_any_future_in_platform_time() {
    let started = tokio::time::Instant::now();
    let platform = Platform::builder()
        .world::<Empty>()
        .environment("mock")
        .backend::<Mock>(|_, _| Ok(MockBackend::new(0.5, true)))
        .behaviour(|pl| async move {
            let (sender, receiver) = tokio::sync::oneshot::channel::<u32>();
            let never = pl.timeout(3600.0, receiver).await;
            assert_eq!(pl.time(), 3600.0, "an hour of platform time");
            assert!(matches!(never, Err(WaitError::Timeout { seconds, .. }) if seconds == 3600.0));
            drop(sender);

            let (sender, receiver) = tokio::sync::oneshot::channel();
            let send_later = async {
                pl.wait_seconds(2.0).await?;
                sender.send(7).map_err(|_| "receiver gone")?;
                Ok::<_, yarok_core::BoxError>(())
            };
            let (sent, received) = tokio::join!(send_later, pl.timeout(5.0, receiver));
            sent?;
            assert_eq!(received??, 7);
            assert_eq!(pl.time(), 3602.0, "it resolved as soon as the value came");

            let joined = pl.timeout(1.0, async {
                pl.wait_seconds(0.5).await?;
                pl.wait_seconds(0.5).await
            });
            assert!(
                joined.await.is_ok(),
                "a deadline on the tick it finishes still lets it"
            );
            let invalid = pl.timeout(f64::NAN, std::future::pending::<()>()).await;
            assert!(matches!(invalid, Err(WaitError::InvalidDuration { .. })));
            Ok(())
        })
        .build()
        .unwrap();
    tokio::task::LocalSet::new()
        .run_until(platform.run_local())
        .await
        .unwrap();
    assert_eq!(
        started.elapsed(),
        std::time::Duration::from_secs(3603),
        "paused tokio time advanced with the ticks"
    );
}
