//! Measures, side by side in one run, the platform loop against a raw `mj_step` loop on the same
//! model: with contacts (a tumble tower of 24 blocks on a floor; target ≥ 95 %) and a bare floor
//! (where only the executor's cost shows; target ≥ 85 %): steps/s of each, their ratio, and the
//! platform's overhead per tick in µs, with ten behaviours each holding a pending wait that is
//! checked every tick. The floor is measured with one pending wait too, which splits its
//! overhead into what every tick costs and what each pending wait adds.
//!
//! ```text
//! cargo bench --bench platform
//! ```

use yarok::components::worlds::TowerWorld;
use yarok::{Component, Declaration};

mod versus_raw;
use versus_raw::{Comparison, compare};

/// Just a floor: stepping is so cheap that the executor's own cost shows.
struct Floor;
impl Component for Floor {
    fn declaration() -> Declaration {
        Declaration::new("floor_world").template(r#"<mujoco><worldbody><geom name="floor" type="plane" size="2 2 0.1"/></worldbody></mujoco>"#)
    }
}

const WAITS: usize = 10;

fn main() {
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
    let per_wait = (floor.overhead_us() - one_wait.overhead_us()) / (WAITS - 1) as f64;
    println!(
        "\nfloor overhead split: {:.3} µs a tick + {:.4} µs a pending wait",
        one_wait.overhead_us() - per_wait,
        per_wait,
    );
    println!(
        "steps/s: each side's fastest round; targets: platform ≥ 95 % of raw with contacts, \
         ≥ 85 % on the floor only (with {WAITS} waits)"
    );
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
