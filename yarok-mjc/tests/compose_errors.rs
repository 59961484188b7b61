//! MuJoCo's errors about a composed world name the component, template, line:column and element
//! the user wrote, not a line of the composed document.

use yarok_core::component::{Component, Declaration};
use yarok_core::compose::compose;
use yarok_mjc::{Model, ModelError};

struct Limb;
impl Component for Limb {
    fn declaration() -> Declaration {
        Declaration::new("limb").template(
            "<mujoco>\n  <worldbody>\n    <body name=\"upper\">\n      <joint name=\"j\"/>\n    </body>\n  </worldbody>\n</mujoco>",
        )
    }
}

struct Bench;
impl Component for Bench {
    fn declaration() -> Declaration {
        Declaration::new("bench").uses::<Limb>().template(
            r#"<mujoco>
                 <worldbody>
                   <geom name="floor" type="plane" size="1 1 0.1"/>
                   <body name="mount" pos="0 0 1"><limb name="left"/></body>
                 </worldbody>
               </mujoco>"#,
        )
    }
}

struct Shelf;
impl Component for Shelf {
    fn declaration() -> Declaration {
        Declaration::new("shelf").template(
            "<mujoco>\n  <worldbody>\n    <geom size=\"0.1\"/>\n    <geom size=\"a b\"/>\n  </worldbody>\n</mujoco>",
        )
    }
}

struct Room;
impl Component for Room {
    fn declaration() -> Declaration {
        Declaration::new("room")
            .uses::<Shelf>()
            .template(r#"<mujoco><worldbody><shelf name="s"/></worldbody></mujoco>"#)
    }
}

fn compile_error<W: Component>() -> (String, String) {
    match Model::from_composition(&compose::<W>().unwrap()) {
        Err(ModelError::Compile { origin, message }) => (origin, message),
        other => panic!("expected a compile error, got {other:?}"),
    }
}

#[test]
fn a_compile_error_names_the_component_template_and_element() {
    let (origin, message) = compile_error::<Bench>();
    assert_eq!(
        origin,
        "component /left, <limb> (inline template):3:5, <body>"
    );
    assert!(
        message.contains("mass and inertia of moving bodies"),
        "{message}"
    );
}

#[test]
fn a_schema_error_names_the_component_template_and_element() {
    let (origin, message) = compile_error::<Room>();
    assert_eq!(
        origin,
        "component /s, <shelf> (inline template):4:5, <geom>"
    );
    assert_eq!(message, "XML Error: bad format in attribute 'size'");
}

struct Shop;
impl Component for Shop {
    fn declaration() -> Declaration {
        Declaration::new("shop")
            .uses::<Crate>()
            .template(r#"<mujoco><worldbody><crate name="c"/></worldbody></mujoco>"#)
    }
}

struct Crate;
impl Component for Crate {
    fn declaration() -> Declaration {
        Declaration::new("crate")
            .template("<mujoco>\n  <asset>\n    <model name=\"inside\"/>\n  </asset>\n</mujoco>")
    }
}

/// An input that would abort MuJoCo is refused first, and named like any compile error.
#[test]
fn an_aborting_input_is_refused_with_its_place() {
    let (origin, message) = compile_error::<Shop>();
    assert_eq!(
        origin,
        "component /c, <crate> (inline template):3:5, <model>"
    );
    assert_eq!(message, "<model> in <asset> needs a `file`");
}

struct Legacy;
impl Component for Legacy {
    fn declaration() -> Declaration {
        Declaration::new("legacy").template(
            "<mujoco>\n  <compiler angle=\"radian\"\n            coordinate=\"global\"/>\n  <worldbody>\n    <body><geom size=\"0.1\"/></body>\n  </worldbody>\n</mujoco>",
        )
    }
}

/// The composer merges every component's settings into one element; MuJoCo's error about it
/// names the template that wrote it, not `<string>` and a composed line.
#[test]
fn an_error_in_merged_settings_names_the_template_that_set_them() {
    let (origin, message) = compile_error::<Legacy>();
    assert_eq!(
        origin,
        "component /, <legacy> (inline template):2:3, <compiler>"
    );
    assert!(
        message.contains("global coordinates no longer supported"),
        "{message}"
    );
}
