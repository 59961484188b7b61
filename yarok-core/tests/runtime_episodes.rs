//! Episodes: the backend and every component put back when one begins, plugins told in order
//! among the logged lines, a backend that cannot go back refusing.

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use yarok_core::BoxError;
use yarok_core::component::{
    Backend, Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, Mock,
    MockBackend,
};
use yarok_core::runtime::{Happening, Platform, Plugin, World};

/// Counts ticks since the start, or since the last episode began.
#[derive(Clone)]
struct Counter(Rc<Cell<u64>>);

impl Component for Counter {
    fn declaration() -> Declaration {
        Declaration::new("counter").template("<mujoco/>")
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Mock>().add::<Frozen>();
    }
}

impl Counter {
    fn bind<E: Environment>(bind: &mut Bind<E>) -> Self {
        let ticks = Rc::new(Cell::new(0));
        let (ticking, restarting) = (Rc::clone(&ticks), Rc::clone(&ticks));
        bind.on_tick(move || {
            ticking.set(ticking.get() + 1);
            Ok(())
        });
        bind.on_restart(move || restarting.set(0));
        Counter(ticks)
    }
}

impl Interface<Mock> for Counter {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Ok(Counter::bind(bind))
    }
}

impl Interface<Frozen> for Counter {
    async fn bind(bind: &mut Bind<Frozen>) -> Result<Self, BindError> {
        Ok(Counter::bind(bind))
    }
}

/// An environment whose world cannot go back to its start.
struct Frozen;
impl Environment for Frozen {
    const NAME: &'static str = "frozen";
    type Backend = FrozenBackend;
}

struct FrozenBackend(MockBackend);
impl Backend for FrozenBackend {
    fn step(&self) -> Result<f64, BoxError> {
        self.0.step()
    }
    fn time(&self) -> f64 {
        self.0.time()
    }
    fn timestep(&self) -> f64 {
        self.0.timestep()
    }
    fn paced(&self) -> bool {
        false
    }
    fn restart(&self) -> Result<(), BoxError> {
        Err("the glacier does not melt back".into())
    }
}

/// Writes down the lines and episode events it sees, in order.
struct Seen(Rc<RefCell<Vec<String>>>);

impl Plugin for Seen {
    fn name(&self) -> String {
        "seen".to_owned()
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        for happening in world.happenings().iter() {
            self.0.borrow_mut().push(match happening {
                Happening::Logged(line) => format!("{} @{}", line.text, line.tick),
                Happening::EpisodeBegan(e) => format!("{} began @{}", e.number, e.start_tick),
                Happening::EpisodeEnded(e) => format!("{} ended @{}", e.number, e.start_tick),
                Happening::TaskSet(task) => format!("task: {task}"),
            });
        }
        Ok(())
    }
}

#[test]
fn an_episode_puts_every_component_back_and_plugins_see_it_among_the_lines() {
    let seen = Rc::new(RefCell::new(Vec::new()));
    Platform::builder()
        .world::<Counter>()
        .environment("mock")
        .backend::<Mock>(|_, _| Ok(MockBackend::new(0.01, false)))
        .plugin(Seen(Rc::clone(&seen)))
        .behaviour(|pl| async move {
            let counter: Counter = pl.get("/")?;
            pl.wait(|| pl.ticks() >= 3).await?;
            assert_eq!(counter.0.get(), 3);
            pl.log("before");
            let episode = pl.begin_episode(5)?;
            assert_eq!((episode.number, episode.start_tick), (5, 3));
            assert_eq!(counter.0.get(), 0, "the component's own state is put back");
            pl.log("in 5");
            pl.wait(|| pl.ticks() >= 5).await?;
            assert_eq!(counter.0.get(), 2);
            assert_eq!(pl.episode(), Some(episode));
            assert_eq!(episode.time_at(pl.ticks(), pl.timestep()), 0.02);
            pl.log("still in 5");
            pl.begin_episode(6)?;
            pl.set_task("count again");
            pl.log("in 6");
            pl.end_episode();
            assert_eq!(pl.episode(), None);
            pl.log("after");
            pl.tick().await?;
            Ok(())
        })
        .run()
        .unwrap();
    assert_eq!(
        *seen.borrow(),
        [
            "before @3",
            "5 began @3",
            "in 5 @3",
            "still in 5 @5",
            "5 ended @3",
            "6 began @5",
            "task: count again",
            "in 6 @5",
            "6 ended @5",
            "after @5"
        ]
    );
}

#[test]
fn an_episode_cannot_begin_where_the_world_cannot_go_back() {
    Platform::builder()
        .world::<Counter>()
        .environment("frozen")
        .backend::<Frozen>(|_, _| Ok(FrozenBackend(MockBackend::new(0.01, false))))
        .behaviour(|pl| async move {
            pl.tick().await?;
            let error = pl.begin_episode(2).unwrap_err();
            assert_eq!(
                error.to_string(),
                "episode 2 cannot begin: the world cannot go back to its start state: the \
                 glacier does not melt back"
            );
            assert_eq!(pl.episode(), None);
            assert_eq!(
                pl.get::<Counter>("/")?.0.get(),
                1,
                "the components are not put back"
            );
            Ok(())
        })
        .run()
        .unwrap();
}
