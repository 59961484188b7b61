//! The tumble tower of the original README: `<for>` loops and the Python-style conditional.

use yarok_components::toys::TumbleTower;
use yarok_core::component::ComponentType;
use yarok_core::compose::{compose, compose_with};
use yarok_core::template::xml::Element;
use yarok_core::value::{Config, IntoValue, Overrides};

fn numbers(element: &Element, attribute: &str) -> Vec<f64> {
    element
        .attribute(attribute)
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect()
}

fn free_bodies(world: &Element) -> Vec<&Element> {
    let worldbody = world.child("worldbody").unwrap();
    worldbody
        .children
        .iter()
        .filter(|b| b.name == "body" && b.child("freejoint").is_some())
        .collect()
}

#[test]
fn eight_rows_make_24_free_blocks_at_the_right_places() {
    let world = compose::<TumbleTower>().unwrap();
    let blocks = free_bodies(&world.mjcf);
    assert_eq!(blocks.len(), 24);
    for (index, block) in blocks.iter().enumerate() {
        let (z, x) = (index / 3, (index % 3) as f64);
        assert_eq!(
            block.attribute("name").unwrap(),
            format!("block_{z}_{}", index % 3)
        );
        let expected = if z % 2 == 0 {
            [0.5 + 0.082 * x, 0.48, 0.0305 + 0.061 * z as f64]
        } else {
            [0.58, 0.4 + 0.082 * x, 0.0305 + 0.061 * z as f64]
        };
        let pos = numbers(block, "pos");
        for (got, want) in pos.iter().zip(expected) {
            assert!(
                (got - want).abs() < 1e-12,
                "{index}: {pos:?} vs {expected:?}"
            );
        }
        let yaw = numbers(block, "euler")[2];
        assert_eq!(yaw, if z % 2 == 0 { 0.0 } else { 1.57 });
        assert_eq!(
            block.child("geom").unwrap().attribute("class"),
            Some("block")
        );
    }
}

#[test]
fn rows_come_from_config() {
    let mut config = Config::from([("rows", 3)]);
    config.set("pos", vec![1.0, -1.0, 0.5].into_value());
    let overrides = Overrides::from([("/".to_owned(), config)]);
    let world = compose_with(ComponentType::of::<TumbleTower>(), &overrides).unwrap();
    let blocks = free_bodies(&world.mjcf);
    assert_eq!(blocks.len(), 9);
    assert_eq!(numbers(blocks[0], "pos"), [1.5, -0.52, 0.5305]);
    assert_eq!(world.instance("/").unwrap().joints.len(), 9);
}
