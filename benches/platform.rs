//! Measures, side by side in one run, the platform loop against a raw `mj_step` loop on the same
//! model: with contacts (a tumble tower of 24 blocks on a floor; target ≥ 95 %) and a bare floor
//! (where only the executor's cost shows; target ≥ 85 %): steps/s of each, their ratio, and the
//! platform's overhead per tick in µs, with ten behaviours each holding a pending wait that is
//! checked every tick. The floor is measured with one pending wait too, which splits its
//! overhead into what every tick costs and what each pending wait adds, and against a bare
//! executor that does nothing but poll ten async waits after each `mj_step`: about the least any
//! executor of such behaviours can cost on this machine.
//!
//! ```text
//! cargo bench --bench platform
//! ```
//!
//! Wall time on the floor-only model moves by several per cent with where the linker places the
//! code (the same source gives different figures in builds that differ elsewhere);
//! `scripts/tick-instructions.sh` counts the instructions of each side instead, which every run
//! of a build repeats to within one a tick. It runs this bench with `--once raw|platform|bare TICKS WAITS`:
//! one side, once, on the floor-only model.

use std::cell::Cell;
use std::future::Future;
use std::pin::Pin;
use std::rc::Rc;
use std::task::{Context, Poll, Waker};
use std::time::Instant;

use yarok::components::worlds::TowerWorld;
use yarok::{Component, Declaration};

mod versus_raw;
use versus_raw::{Comparison, compare, compare_with, fresh_data, platform_seconds, raw_seconds};

/// Just a floor: stepping is so cheap that the executor's own cost shows.
struct Floor;
impl Component for Floor {
    fn declaration() -> Declaration {
        Declaration::new("floor_world").template(r#"<mujoco><worldbody><geom name="floor" type="plane" size="2 2 0.1"/></worldbody></mujoco>"#)
    }
}

const WAITS: usize = 10;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(at) = args.iter().position(|arg| arg == "--once") {
        run_once(&args[at + 1..]);
        return;
    }
    println!("{WAITS} behaviours each hold a pending wait, checked every tick\n");
    println!(
        "{:<34} {:>12} {:>12} {:>7} {:>14} {:>13}",
        "model", "raw steps/s", "platform", "ratio", "overhead/tick", "median ratio"
    );
    print_row(
        "tumble tower (24 blocks, contacts)",
        &compare::<TowerWorld>(WAITS, |_| {}),
    );
    let floor = compare::<Floor>(WAITS, |_| {});
    print_row("floor only (executor cost shows)", &floor);
    let one_wait = compare::<Floor>(1, |_| {});
    print_row("floor only, 1 pending wait", &one_wait);
    let bare = compare_with::<Floor>(|_| {}, |ticks| bare_seconds::<Floor>(ticks, WAITS));
    print_row("floor only, bare executor", &bare);
    let per_wait = (floor.overhead_us() - one_wait.overhead_us()) / (WAITS - 1) as f64;
    println!(
        "\nfloor overhead split: {:.3} µs a tick + {:.4} µs a pending wait",
        one_wait.overhead_us() - per_wait,
        per_wait,
    );
    println!(
        "the platform's overhead over the bare executor's: {:.3} µs a tick",
        floor.overhead_us() - bare.overhead_us()
    );
    println!(
        "steps/s: each side's fastest round; targets: platform ≥ 95 % of raw with contacts, \
         ≥ 85 % on the floor only (with {WAITS} waits)"
    );
}

/// `raw|platform|bare TICKS WAITS`: that side's run on the floor-only model, once.
fn run_once(args: &[String]) {
    let usage = "usage: --once raw|platform|bare TICKS WAITS";
    let [side, ticks, waits] = args else {
        panic!("{usage}");
    };
    let (Ok(ticks), Ok(waits)) = (ticks.parse(), waits.parse()) else {
        panic!("{usage}");
    };
    match side.as_str() {
        "raw" => raw_seconds::<Floor>(ticks, |_| {}),
        "platform" => platform_seconds::<Floor>(ticks, waits),
        "bare" => bare_seconds::<Floor>(ticks, waits),
        _ => panic!("{usage}"),
    };
}

fn print_row(name: &str, measured: &Comparison) {
    println!(
        "{name:<34} {:>12.0} {:>12.0} {:>6.1}% {:>11.3} µs {:>12.1}%   ({} rounds × {} steps)",
        measured.raw,
        measured.platform,
        100.0 * measured.ratio(),
        measured.overhead_us(),
        100.0 * measured.median_ratio,
        measured.rounds,
        measured.ticks,
    );
}

/// A task of the bare executor.
type BareTask = Pin<Box<dyn Future<Output = ()>>>;

/// Tick state of the bare executor: the tick count, and whether the task being polled waits.
#[derive(Default)]
struct BareClock {
    ticks: Cell<u64>,
    registered: Cell<bool>,
}

/// A wait with nothing but a condition checked once a tick: no timeout, no stop, no waker.
struct BareWait<'a, C> {
    clock: &'a BareClock,
    seen_tick: u64,
    condition: C,
}

impl<C: FnMut() -> bool + Unpin> Future for BareWait<'_, C> {
    type Output = ();

    fn poll(self: Pin<&mut Self>, _: &mut Context<'_>) -> Poll<()> {
        let this = self.get_mut();
        let ticks = this.clock.ticks.get();
        if ticks > this.seen_tick {
            this.seen_tick = ticks;
            if (this.condition)() {
                return Poll::Ready(());
            }
        }
        this.clock.registered.set(true);
        Poll::Pending
    }
}

/// Seconds for `ticks` ticks of a bare executor: `mj_step`, then poll `waits` boxed
/// async blocks that each await a [`BareWait`], as the platform's behaviours do — without
/// errors, a stop flag, I/O wake-ups, plugins or turns for tokio. Timed as the platform is: by the
/// first block, from its first poll to the tick its wait resolves on.
fn bare_seconds<W: Component>(ticks: u64, waits: usize) -> f64 {
    let mut data = fresh_data::<W>(|_| {});
    let clock = Rc::new(BareClock::default());
    let elapsed = Rc::new(Cell::new(f64::NAN));
    let mut tasks: Vec<(BareTask, bool)> = (0..waits)
        .map(|index| {
            let (clock, elapsed) = (Rc::clone(&clock), Rc::clone(&elapsed));
            let task: BareTask = Box::pin(async move {
                let started = Instant::now();
                let condition = || clock.ticks.get() >= ticks;
                let seen_tick = clock.ticks.get();
                BareWait {
                    clock: &clock,
                    seen_tick,
                    condition,
                }
                .await;
                if index == 0 {
                    elapsed.set(started.elapsed().as_secs_f64());
                }
            });
            (task, true)
        })
        .collect();
    let mut context = Context::from_waker(Waker::noop());
    let mut first_done = false;
    while !first_done {
        for (task, waits_tick) in &mut tasks {
            if *waits_tick {
                clock.registered.set(false);
                first_done |= task.as_mut().poll(&mut context).is_ready();
                *waits_tick = clock.registered.get();
            }
        }
        data.step();
        clock.ticks.set(clock.ticks.get() + 1);
    }
    elapsed.get()
}
