//! The components' commands — what the Zenoh bridge runs for every command it receives — on
//! 100 000 generated bodies in a DigitWorld in `sim` (the UR5e, the 2F-85 and the DIGITs): arm
//! motions and grips with numbers of every size, fields of the wrong kind, unknown fields,
//! missing values and commands to paths and names nobody takes. Each is answered, taken or
//! refused with a message, a hundred a tick while the world runs on; none panics, none stops
//! the world, and the run ends within its bound. `YAROK_FUZZ_INPUTS` sets how many.

use std::cell::Cell;
use std::rc::Rc;
use std::time::{Duration, Instant};

use serde_json::{Map, Value, json};
use yarok::components::worlds::DigitWorld;
use yarok::{BoxError, Plugin, World};
use yarok_test::generator::{Generator, fuzz_inputs};

/// Commands run each tick.
const PER_TICK: usize = 100;

/// The longest the whole run may take.
const BOUND: Duration = Duration::from_secs(600);

/// A number a command may hold: plausible, extreme or nonsensical.
fn number(generator: &mut Generator) -> Value {
    let extreme = [
        0.0, -0.0, 1.0, -1.0, 0.5, 3.2, 6.3, 255.0, 256.0, -1e-300, 1e308, -1e308, 1e-9, 127.5,
    ];
    match generator.below(3) {
        0 => json!(extreme[generator.below(extreme.len())]),
        1 => json!((generator.next_u64() as i64) >> generator.below(64)),
        _ => json!((generator.next_u64() as f64 / u64::MAX as f64 - 0.5) * 8.0),
    }
}

/// A value of any kind, `depth` levels deep at most.
fn value(generator: &mut Generator, depth: usize) -> Value {
    match generator.below(if depth == 0 { 4 } else { 7 }) {
        0 | 1 => number(generator),
        2 => json!(generator.below(2) == 0),
        3 => [Value::Null, json!(""), json!("move_j"), json!("ü\u{0}")][generator.below(4)].clone(),
        4 | 5 => (0..generator.below(9))
            .map(|_| value(generator, depth - 1))
            .collect(),
        _ => body(generator, depth - 1),
    }
}

/// A command's body: an object of the fields the arm and the gripper take (and others), or now
/// and then something that is no object.
fn body(generator: &mut Generator, depth: usize) -> Value {
    if generator.below(20) == 0 {
        return value(generator, depth.min(1));
    }
    if generator.below(3) == 0 {
        return plausible(generator);
    }
    let fields = [
        "move_j",
        "move_l",
        "stop",
        "speed",
        "acceleration",
        "move_to",
        "open",
        "close",
        "force",
        "ping",
        "q",
    ];
    let mut object = Map::new();
    for _ in 0..generator.below(4) {
        let field = generator.pick(&fields);
        let joints = generator.below(3) == 0;
        let entry = if joints && (field == "move_j" || field == "move_l") {
            (0..6).map(|_| number(generator)).collect()
        } else {
            value(generator, depth)
        };
        object.insert(field.to_owned(), entry);
    }
    Value::Object(object)
}

/// A command as a client means it: a motion or a grip of sensible values, some out of reach.
fn plausible(generator: &mut Generator) -> Value {
    let kind = generator.below(6);
    let mut unit = || generator.next_u64() as f64 / u64::MAX as f64 - 0.5;
    let mut command = match kind {
        0 => json!({ "move_j": (0..6).map(|_| 4.0 * unit()).collect::<Vec<_>>() }),
        1 => {
            let home = [0.4, 0.1, 0.4, 0.0, std::f64::consts::PI, 0.0];
            let pose: Vec<f64> = home.iter().map(|h| h + 0.4 * unit()).collect();
            json!({ "move_l": pose })
        }
        2 => json!({ "stop": true }),
        3 => json!({ "move_to": (300.0 * (unit() + 0.5)).round() }),
        4 => json!({ "open": true }),
        _ => json!({ "close": true }),
    };
    if unit() > 0.0 {
        command["speed"] = json!(((unit() + 0.5) * 400.0).round() / 100.0);
    }
    command
}

/// Runs the generated commands, [`PER_TICK`] a tick, and stops the world after the last.
struct Fuzzer {
    generator: Generator,
    left: usize,
    /// How many were taken and refused, read by the test once the run ends.
    taken: Rc<Cell<usize>>,
    refused: Rc<Cell<usize>>,
}

impl Plugin for Fuzzer {
    fn name(&self) -> String {
        "command fuzzer".into()
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let commands = world.commands();
        assert!(!commands.is_empty(), "the world takes no commands");
        for _ in 0..PER_TICK.min(self.left) {
            self.left -= 1;
            let body = body(&mut self.generator, 2);
            let command = &commands[self.generator.below(commands.len())];
            let (path, name) = match self.generator.below(20) {
                0 => ("/nobody".to_owned(), command.name().to_owned()),
                1 => (command.component().to_owned(), "nothing".to_owned()),
                _ => (command.component().to_owned(), command.name().to_owned()),
            };
            match world.command(&path, &name) {
                Some(command) => match command.run(body.clone()) {
                    Ok(()) => self.taken.set(self.taken.get() + 1),
                    Err(error) => {
                        let said = error.to_string();
                        assert!(
                            !said.trim().is_empty(),
                            "{path} {name} {body}: an empty error"
                        );
                        self.refused.set(self.refused.get() + 1);
                    }
                },
                None => self.refused.set(self.refused.get() + 1),
            }
        }
        if self.left == 0 {
            world.pl().stop();
        }
        Ok(())
    }
}

#[test]
fn generated_commands_are_taken_or_refused_and_the_world_runs_on() {
    let total = fuzz_inputs();
    let (taken, refused) = (Rc::new(Cell::new(0)), Rc::new(Cell::new(0)));
    let started = Instant::now();
    let result = yarok::platform()
        .world::<DigitWorld>()
        .plugin(Fuzzer {
            generator: Generator(0xc0de_f022),
            left: total,
            taken: Rc::clone(&taken),
            refused: Rc::clone(&refused),
        })
        .behaviour(|pl| async move {
            pl.wait(|| false).await?;
            Ok(())
        })
        .run();
    let elapsed = started.elapsed();
    let (taken, refused) = (taken.get(), refused.get());
    eprintln!("{total} commands in {elapsed:?}: {taken} taken, {refused} refused");
    assert!(
        matches!(&result, Err(error) if error.to_string().contains("stopped")) || result.is_ok(),
        "{result:?}"
    );
    assert_eq!(taken + refused, total);
    assert!(
        taken > total / 100 && refused > total / 2,
        "{taken} taken, {refused} refused"
    );
    assert!(elapsed < BOUND, "{total} commands took {elapsed:?}");
}
