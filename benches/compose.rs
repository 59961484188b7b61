//! Measures, side by side in one run, composing `PickAndPlaceWorld` (a floor world, a UR5e on a
//! stand with a Robotiq 2F-85 — tendon, equalities, contact exclusions — on its flange, three
//! blocks and a target) against parsing the composed MJCF back and against MuJoCo compiling it.
//! Target: compose ≤ 1 ms (the Python original takes about 9 ms for the template build of its
//! DigitUR5World, which adds two tactile sensors to such a world).
//!
//! ```text
//! cargo bench --bench compose
//! ```

use std::time::Duration;

use yarok::components::worlds::PickAndPlaceWorld;
use yarok::core::compose::compose;
use yarok::core::template::xml::Element;
use yarok::mjc::Model;

mod measure;
use measure::mean_times;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let composition = compose::<PickAndPlaceWorld>()?;
    let xml = composition.to_xml();
    let model = Model::from_composition(&composition)?;
    println!(
        "world: {} components, {} elements, {} bodies in MuJoCo",
        composition.instances.len(),
        composition.mjcf.descendants().len(),
        model.count(yarok::mjc::ObjectKind::Body)
    );
    let [compose_time, parse_time, compile_time] = mean_times(|variant| match variant {
        0 => compose::<PickAndPlaceWorld>()
            .expect("compose")
            .instances
            .len(),
        1 => Element::parse(&xml).expect("parse").root.children.len(),
        _ => Model::from_composition(&composition)
            .expect("compile")
            .count(yarok::mjc::ObjectKind::Body),
    });
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    println!("\n{:<34} {:>10}", "step", "ms");
    println!(
        "{:<34} {:>10.3}",
        "compose (templates → MJCF)",
        ms(compose_time)
    );
    println!("{:<34} {:>10.3}", "parse the composed MJCF", ms(parse_time));
    println!(
        "{:<34} {:>10.3}",
        "MuJoCo compile (2 passes: keys)",
        ms(compile_time)
    );
    println!(
        "\ncompose / parse   = {:.1}x",
        ms(compose_time) / ms(parse_time)
    );
    println!(
        "compose / compile = {:.3}x",
        ms(compose_time) / ms(compile_time)
    );
    println!("compose / 1 ms target = {:.2}", ms(compose_time));
    Ok(())
}
