//! A user's own environment for a bundled device, added in this file alone: `replay`, in which
//! the AnetA30 printer's head follows a recorded track instead of physics or a serial port. The
//! printer's handle is untouched: the environment is an implementation of its drive
//! ([`AxesDrive`]), and the same behaviour runs in `sim` and in `replay`.

use std::cell::RefCell;
use std::rc::Rc;

use yarok::components::robots::{AnetA30, AxesDrive};
use yarok::core::component::{Environment, MockBackend};
use yarok::core::time::Clock;
use yarok::mjc::Sim;
use yarok::prelude::*;

/// Runs that replay a recording.
struct Replay;

impl Environment for Replay {
    const NAME: &'static str = "replay";
    type Backend = MockBackend;
}

/// Where the head was at each recorded time (seconds, millimetres), and what the behaviour
/// commanded while it was replayed.
struct ReplayedAxes {
    clock: Clock,
    track: Vec<(f64, [f64; 3])>,
    commanded: RefCell<Vec<[f64; 3]>>,
}

impl AxesDrive for ReplayedAxes {
    fn move_to(&self, target: [f64; 3]) {
        self.commanded.borrow_mut().push(target);
    }

    fn at(&self) -> [f64; 3] {
        let now = self.clock.time();
        let passed = self.track.iter().take_while(|(time, _)| *time <= now);
        passed.last().map_or([0.0; 3], |(_, at)| *at)
    }
}

/// The bundled printer, with `replay` beside its `sim`.
#[derive(Clone)]
struct Printer {
    head: AnetA30,
    replayed: Option<Rc<ReplayedAxes>>,
}

impl Component for Printer {
    fn declaration() -> Declaration {
        AnetA30::declaration()
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Sim>().add::<Replay>();
    }
}

impl Interface<Sim> for Printer {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let head = <AnetA30 as Interface<Sim>>::bind(bind).await?;
        Ok(Printer {
            head,
            replayed: None,
        })
    }
}

impl Interface<Replay> for Printer {
    async fn bind(bind: &mut Bind<Replay>) -> Result<Self, BindError> {
        // A recording of the head going to (100, 120, 50) in a straight line over a second.
        let track = (0..=100)
            .map(|step| {
                let along = f64::from(step) / 100.0;
                (along, [100.0 * along, 120.0 * along, 50.0 * along])
            })
            .collect();
        let axes = Rc::new(ReplayedAxes {
            clock: bind.clock(),
            track,
            commanded: RefCell::new(Vec::new()),
        });
        Ok(Printer {
            head: AnetA30::with_drive(bind, Rc::clone(&axes) as Rc<dyn AxesDrive>),
            replayed: Some(axes),
        })
    }
}

/// The behaviour: send the head to (100, 120, 50) and wait until it is there. Returns when it
/// arrived (platform seconds) and what the drive was commanded.
fn go_to_the_corner(environment: &str) -> (f64, Vec<[f64; 3]>) {
    let outcome = Rc::new(RefCell::new(None));
    let out = Rc::clone(&outcome);
    yarok::platform()
        .world::<Printer>()
        .backend::<Replay>(|_, _| Ok(MockBackend::new(0.002, false)))
        .environment(environment)
        .behaviour(move |pl| async move {
            let printer: Printer = pl.get("/")?;
            let target = [100.0, 120.0, 50.0];
            printer.head.move_to(target);
            pl.wait(|| printer.head.is_at(target)).timeout(5.0).await?;
            let commanded = printer
                .replayed
                .map(|axes| axes.commanded.borrow().clone())
                .unwrap_or_default();
            *out.borrow_mut() = Some((pl.time(), commanded));
            Ok(())
        })
        .run()
        .unwrap();
    outcome.take().expect("the behaviour ran")
}

#[test]
fn the_same_behaviour_runs_on_a_replayed_printer_and_a_simulated_one() {
    let (replayed_at, commanded) = go_to_the_corner("replay");
    // The recording reaches the corner at 1.0 s; the head is "there" within 0.25 mm of it.
    assert!((0.99..=1.0 + 1e-9).contains(&replayed_at), "{replayed_at}");
    assert_eq!(commanded, vec![[100.0, 120.0, 50.0]]);
    let (simulated_at, nothing) = go_to_the_corner("sim");
    assert!(simulated_at > 0.0 && simulated_at < 5.0, "{simulated_at}");
    assert!(nothing.is_empty());
}
