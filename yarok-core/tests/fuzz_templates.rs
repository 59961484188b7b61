//! Property tests: no expression and no template makes the composer panic or overflow its stack
//! (self-using components, deep nesting and long expressions included); every failure is an error
//! value. `PROPTEST_CASES=100000 cargo test -p yarok-core --release --test fuzz_templates` runs
//! many more cases than CI does.

use proptest::prelude::*;
use yarok_core::component::{Component, Declaration};
use yarok_core::compose::compose_declaration;
use yarok_core::config::Settings;
use yarok_core::template::expr::{Expr, Variables};
use yarok_core::template::xml::Element;

struct NoVariables;
impl Variables for NoVariables {
    fn get(&self, _: &str) -> Option<&yarok_core::value::Value> {
        None
    }
}

struct Leaf;
impl Component for Leaf {
    fn declaration() -> Declaration {
        Declaration::new("leaf").default("k", 1).template(
            r#"<mujoco><worldbody><body name="b"><geom size="{k}"/></body></worldbody></mujoco>"#,
        )
    }
}

/// A component that contains itself (always refused, whatever its config).
struct Selfish;
impl Component for Selfish {
    fn declaration() -> Declaration {
        Declaration::new("selfish").default("k", 1).uses::<Selfish>().template(
            r#"<mujoco><worldbody><if the="k > 0"><selfish name="s" k="{k - 1}"/></if></worldbody></mujoco>"#,
        )
    }
}

/// Fragments that make interesting Python expressions when strung together.
fn expression() -> impl Strategy<Value = String> {
    let atom = prop_oneof![
        Just("1".to_owned()),
        Just("2.5".to_owned()),
        Just("-3".to_owned()),
        Just("'s'".to_owned()),
        Just("True".to_owned()),
        Just("None".to_owned()),
        Just("[1, 2]".to_owned()),
        Just("range(3)".to_owned()),
        Just("k".to_owned()),
        Just("9223372036854775807".to_owned()),
        Just("1e308".to_owned()),
    ];
    let op = prop_oneof![
        Just(" + "),
        Just(" - "),
        Just(" * "),
        Just(" / "),
        Just(" // "),
        Just(" % "),
        Just(" ** "),
        Just(" == "),
        Just(" < "),
        Just(" and "),
        Just(" or "),
        Just(" in "),
        Just(" if "),
        Just(" else "),
        Just("["),
        Just("]"),
        Just("("),
        Just(")"),
        Just(", "),
        Just(":"),
        Just("not "),
        Just("len("),
    ];
    prop::collection::vec((atom, op), 1..8)
        .prop_map(|parts| parts.into_iter().map(|(a, o)| format!("{a}{o}")).collect())
}

/// Random templates built from MJCF, control constructs and a component tag.
fn template() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        expression().prop_map(|e| format!(r#"<geom size="{{{e}}}"/>"#)),
        expression().prop_map(|e| format!(r#"<site name="s" if="{}"/>"#, e.replace('"', "'"))),
        Just(r#"<leaf name="l"/>"#.to_owned()),
        Just(r#"<leaf name="{k}" k="{[1]}"/>"#.to_owned()),
        Just(r#"<site parent="b"/>"#.to_owned()),
        Just("<geom size='{'/>".to_owned()),
        Just("<geom size='}'/>".to_owned()),
        Just(r#"<selfish name="s"/>"#.to_owned()),
        (1..3000usize).prop_map(|n| format!(r#"<geom size="{{{}}}"/>"#, vec!["k"; n].join(" + "))),
        (1..3000usize).prop_map(|n| format!(r#"<site if="{}"/>"#, vec!["k"; n].join(" and "))),
        (1..700usize).prop_map(|n| format!("{}{}", "<body>".repeat(n), "</body>".repeat(n))),
    ];
    leaf.prop_recursive(4, 24, 4, |inner| {
        prop::collection::vec(inner, 0..4).prop_flat_map(|children| {
            let body = children.concat();
            prop_oneof![
                Just(format!(r#"<body name="b">{body}</body>"#)),
                Just(format!(r#"<for each="range(2)" as="i">{body}</for>"#)),
                Just(format!(r#"<for each="k" as="i">{body}</for>"#)),
                Just(format!(r#"<if the="k">{body}</if>"#)),
                Just(format!(r#"<leaf name="n">{body}</leaf>"#)),
                Just(format!("<for>{body}</for>")),
            ]
        })
    })
    .prop_map(|body| format!("<mujoco><worldbody>{body}</worldbody><actuator><for each='range(2)' as='j'><motor joint='{{j}}'/></for></actuator></mujoco>"))
}

fn compose_text(text: String) {
    let world = Declaration::new("world")
        .default("k", 2)
        .uses::<Leaf>()
        .uses::<Selfish>()
        .template(text);
    if let Ok(composition) = compose_declaration(world, &Settings::default()) {
        Element::parse(&composition.to_xml()).expect("composed MJCF parses back");
    }
}

proptest! {
    #[test]
    fn expressions_never_panic(source in expression()) {
        if let Ok(expr) = Expr::parse(&source) {
            let _ = expr.eval(&NoVariables);
        }
    }

    #[test]
    fn arbitrary_text_never_panics_the_expression_parser(source in ".{0,60}") {
        let _ = Expr::parse(&source).map(|e| e.eval(&NoVariables));
    }

    #[test]
    fn generated_templates_never_panic(text in template()) {
        compose_text(text);
    }

    #[test]
    fn arbitrary_text_as_a_template_never_panics(text in ".{0,200}") {
        compose_text(format!("<mujoco><worldbody>{text}</worldbody></mujoco>"));
        compose_text(text);
    }
}
