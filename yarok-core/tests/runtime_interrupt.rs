//! Ctrl-C ends a run cleanly. Alone in its file, so that the signal reaches no other test's
//! platform (each test file is its own process).

use std::cell::Cell;
use std::rc::Rc;

use yarok_core::compose::{Component, Declaration};
use yarok_core::runtime::{BoxError, MockBackend, Pl, Platform, Plugin, RuntimeError};

struct Empty;
impl Component for Empty {
    fn declaration() -> Declaration {
        Declaration::new("empty").template("<mujoco><worldbody/></mujoco>")
    }
}

struct Watch(Rc<Cell<bool>>);

impl Plugin for Watch {
    fn step(&mut self, _: &Pl) -> Result<(), BoxError> {
        Ok(())
    }

    fn on_end(&mut self, _: &Pl) {
        self.0.set(true);
    }
}

#[test]
fn ctrl_c_stops_the_run_and_plugins_see_the_end() {
    let ended = Rc::new(Cell::new(false));
    let error = Platform::builder()
        .world::<Empty>()
        // Paced, so that ticks take real time and the signal has time to arrive.
        .backend("sim", |_, _| Ok(Box::new(MockBackend::new(0.01, true))))
        .plugin(Watch(Rc::clone(&ended)))
        .behaviour(|pl| async move {
            pl.wait_seconds(0.1).await?;
            let status = std::process::Command::new("kill")
                .args(["-INT", &std::process::id().to_string()])
                .status()?;
            assert!(status.success());
            pl.wait_forever().timeout(10.0).await?;
            Ok(())
        })
        .run()
        .unwrap_err();
    assert!(matches!(error, RuntimeError::Interrupted), "{error}");
    assert!(ended.get());
}
