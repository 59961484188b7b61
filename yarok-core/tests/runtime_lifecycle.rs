//! An interface's life: async bind (connect to a device), tasks that live as long as the run,
//! I/O reaching behaviours at once, and stop actions that always run.

mod device;

use std::time::Duration;

use device::{Device, Lab, Server};
use yarok_core::component::{BindError, Component, Declaration, MockBackend};
use yarok_core::runtime::{Platform, PlatformBuilder, RuntimeError};

/// Two devices, `/a` and `/b`.
struct Bench;
impl Component for Bench {
    fn declaration() -> Declaration {
        Declaration::new("bench").uses::<Device>().template(
            r#"<mujoco><worldbody><device name="a"/><device name="b"/></worldbody></mujoco>"#,
        )
    }
}

/// A paced lab platform whose devices talk to `a` and `b`; ticks of `tick` seconds.
fn lab(a: u16, b: u16, tick: f64) -> PlatformBuilder {
    Platform::builder()
        .world::<Bench>()
        .environment("lab")
        .backend::<Lab>(move |_, _| Ok(MockBackend::new(tick, true)))
        .set(&format!("interfaces/a/port={a}"))
        .unwrap()
        .set(&format!("interfaces/b/port={b}"))
        .unwrap()
}

#[test]
fn devices_are_told_to_stop_when_the_behaviours_return() {
    let (a, b) = (Server::start(None), Server::start(None));
    lab(a.port(), b.port(), 0.01)
        .behaviour(|pl| async move {
            pl.wait_seconds(0.05).await?;
            Ok(())
        })
        .run()
        .unwrap();
    assert_eq!(a.received(1), ["STOP"]);
    assert_eq!(b.received(1), ["STOP"]);
}

#[test]
fn devices_are_told_to_stop_when_a_behaviour_fails() {
    let (a, b) = (Server::start(None), Server::start(None));
    let error = lab(a.port(), b.port(), 0.01)
        .behaviour(|pl| async move {
            pl.tick().await?;
            Err("the gripper slipped".into())
        })
        .run()
        .unwrap_err();
    assert!(matches!(error, RuntimeError::Behaviour { .. }), "{error}");
    assert_eq!(a.received(1), ["STOP"]);
    assert_eq!(b.received(1), ["STOP"]);
}

#[test]
fn a_stop_action_that_fails_does_not_keep_the_others_from_running() {
    let (a, b) = (Server::start(None), Server::start(None));
    let error = lab(a.port(), b.port(), 0.01)
        .set("interfaces/a/refuse_to_stop=true")
        .unwrap()
        .behaviour(|pl| async move {
            pl.tick().await?;
            Ok(())
        })
        .run()
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "component /a did not stop cleanly: the device refused to stop"
    );
    assert_eq!(a.received(1), ["STOP"]);
    assert_eq!(b.received(1), ["STOP"], "/b still stopped");
}

#[test]
fn a_component_that_fails_to_bind_leaves_those_bound_before_it_safe() {
    let b = Server::start(None);
    let closed = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let closed_port = closed.local_addr().unwrap().port();
    drop(closed);
    let error = lab(closed_port, b.port(), 0.01)
        .behaviour(|_| async move { panic!("behaviours do not start when binding fails") })
        .run()
        .unwrap_err();
    assert!(
        matches!(&error, RuntimeError::Bind(BindError::Failed { component, .. }) if component == "/a"),
        "{error}"
    );
    assert_eq!(b.received(1), ["STOP"], "/b bound first, and was stopped");
}

#[test]
fn io_reaches_a_waiting_behaviour_at_once_not_a_tick_later() {
    let (a, b) = (
        Server::start(Some(Duration::from_millis(50))),
        Server::start(None),
    );
    let started = std::time::Instant::now();
    lab(a.port(), b.port(), 0.5)
        .behaviour(|pl| async move {
            let device: Device = pl.get("/a")?;
            let line = pl.timeout(2.0, device.next_line()).await?;
            assert_eq!(line, "PING");
            assert_eq!(pl.ticks(), 0, "no tick (0.5 s) has passed");
            Ok(())
        })
        .run()
        .unwrap();
    assert!(
        started.elapsed() < Duration::from_millis(400),
        "{:?}",
        started.elapsed()
    );
}

#[test]
fn a_platform_stepped_and_dropped_midway_still_stops_its_devices() {
    let (a, b) = (Server::start(None), Server::start(None));
    let mut platform = lab(a.port(), b.port(), 0.001)
        .behaviour(|pl| async move {
            pl.wait_forever().await?;
            Ok(())
        })
        .build()
        .unwrap();
    for _ in 0..3 {
        assert!(platform.step().unwrap());
    }
    let device: Device = platform.pl().get("/b").unwrap();
    drop(device);
    drop(platform);
    assert_eq!(a.received(1), ["STOP"]);
    assert_eq!(b.received(1), ["STOP"]);
}

/// Counts ticks in a task of its own: per-tick work that awaits.
#[derive(Clone)]
struct Ticker {
    count: std::rc::Rc<std::cell::Cell<u64>>,
}

impl Component for Ticker {
    fn declaration() -> Declaration {
        Declaration::new("ticker").template("<mujoco/>")
    }

    fn interfaces(interfaces: &mut yarok_core::component::Interfaces<Self>) {
        interfaces.add::<yarok_core::component::Mock>();
    }
}

impl yarok_core::component::Interface<yarok_core::component::Mock> for Ticker {
    async fn bind(
        bind: &mut yarok_core::component::Bind<yarok_core::component::Mock>,
    ) -> Result<Self, BindError> {
        let ticker = Ticker {
            count: std::rc::Rc::default(),
        };
        let (clock, count) = (bind.clock(), std::rc::Rc::clone(&ticker.count));
        let device = tokio::sync::Mutex::new(0u64);
        bind.spawn(async move {
            loop {
                clock.tick().await?;
                let mut reading = device.lock().await; // an asynchronous resource
                *reading += 1;
                count.set(*reading);
            }
        });
        Ok(ticker)
    }
}

#[test]
fn an_interface_task_that_awaits_runs_every_tick_before_behaviours_see_it() {
    Platform::builder()
        .world::<Ticker>()
        .environment("mock")
        .backend::<yarok_core::component::Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
        .behaviour(|pl| async move {
            let ticker: Ticker = pl.get("/")?;
            for _ in 0..300 {
                pl.tick().await?;
                assert_eq!(ticker.count.get(), pl.ticks());
            }
            Ok(())
        })
        .run()
        .unwrap();
}
