//! Components that contain themselves, `extends` cycles and worlds nested too deep are errors that
//! say where, never a stack overflow.

use yarok_core::component::{Component, Declaration};
use yarok_core::compose::{ComposeError, compose};

fn error_of<C: Component>() -> ComposeError {
    compose::<C>().expect_err("composition should fail")
}

struct Mirror;
impl Component for Mirror {
    fn declaration() -> Declaration {
        Declaration::new("mirror")
            .uses::<Mirror>()
            .template(r#"<mujoco><worldbody><mirror name="inner"/></worldbody></mujoco>"#)
    }
}

struct Room;
impl Component for Room {
    fn declaration() -> Declaration {
        Declaration::new("room")
            .uses::<Mirror>()
            .template(r#"<mujoco><worldbody><mirror name="m"/></worldbody></mujoco>"#)
    }
}

#[test]
fn a_component_that_uses_itself_is_named_with_its_chain() {
    let error = error_of::<Room>();
    assert_eq!(error.component, "/m");
    assert_eq!(error.element.as_deref(), Some("mirror"));
    assert_eq!(error.attribute.as_deref(), Some("name"));
    assert_eq!(
        error.message,
        "component <mirror> uses itself: /m/inner is inside /m, another <mirror>"
    );
    let world = error_of::<Mirror>();
    assert_eq!(
        world.message,
        "component <mirror> uses itself: /inner is inside the world, another <mirror>"
    );
}

struct Chicken;
struct Egg;
impl Component for Chicken {
    fn declaration() -> Declaration {
        Declaration::new("chicken").uses::<Egg>().template(
            r#"<mujoco><worldbody><body name="b"><egg name="e"/></body></worldbody></mujoco>"#,
        )
    }
}
impl Component for Egg {
    fn declaration() -> Declaration {
        Declaration::new("egg")
            .uses::<Chicken>()
            .template(r#"<mujoco><worldbody><chicken name="c"/></worldbody></mujoco>"#)
    }
}

struct Farm;
impl Component for Farm {
    fn declaration() -> Declaration {
        Declaration::new("farm")
            .uses::<Chicken>()
            .template(r#"<mujoco><worldbody><chicken name="c"/></worldbody></mujoco>"#)
    }
}

#[test]
fn a_component_that_uses_itself_through_another_is_named_with_its_chain() {
    let error = error_of::<Farm>();
    assert_eq!(error.component, "/c/e");
    assert_eq!(
        error.message,
        "component <chicken> uses itself: /c/e/c is inside /c, another <chicken>"
    );
}

struct Ouroboros;
struct Tail;
impl Component for Ouroboros {
    fn declaration() -> Declaration {
        Declaration::new("ouroboros")
            .extends::<Tail>()
            .template("<mujoco/>")
    }
}
impl Component for Tail {
    fn declaration() -> Declaration {
        Declaration::new("tail")
            .extends::<Ouroboros>()
            .template("<mujoco/>")
    }
}

#[test]
fn an_extends_cycle_is_an_error() {
    let error = error_of::<Ouroboros>();
    assert_eq!(error.component, "/");
    assert!(
        error.message.ends_with("extends itself: compose_nesting::Ouroboros → compose_nesting::Tail → compose_nesting::Ouroboros"),
        "{}",
        error.message
    );
}

/// Declares `$name` using `$next` inside a body, so each level adds a component and an element.
macro_rules! tower {
    ($name:ident) => {
        struct $name;
        impl Component for $name {
            fn declaration() -> Declaration {
                Declaration::new(stringify!($name).to_lowercase())
                    .template(r#"<mujoco><worldbody><body name="top"/></worldbody></mujoco>"#)
            }
        }
    };
    ($name:ident, $next:ident $(, $rest:ident)*) => {
        struct $name;
        impl Component for $name {
            fn declaration() -> Declaration {
                let next = stringify!($next).to_lowercase();
                Declaration::new(stringify!($name).to_lowercase())
                    .uses::<$next>()
                    .template(format!(
                        r#"<mujoco><worldbody><body name="b"><{next} name="n"/></body></worldbody></mujoco>"#
                    ))
            }
        }
        tower!($next $(, $rest)*);
    };
}

tower!(
    L00, L01, L02, L03, L04, L05, L06, L07, L08, L09, L10, L11, L12, L13, L14, L15, L16, L17, L18,
    L19, L20, L21, L22, L23, L24, L25, L26, L27, L28, L29, L30, L31, L32, L33, L34, L35, L36, L37
);

#[test]
fn components_nested_too_deep_stop_with_an_error() {
    let error = error_of::<L00>();
    assert_eq!(error.component, format!("/n{}", "/n".repeat(30)));
    assert!(
        error.message.ends_with("nests components deeper than 32"),
        "{}",
        error.message
    );
    assert!(compose::<L10>().is_ok(), "27 levels compose");
}

/// A template whose body nests 200 bodies, used in a chain of three: 600 levels in the world.
struct Deep<const N: usize>;
impl<const N: usize> Component for Deep<N> {
    fn declaration() -> Declaration {
        let inner = if N == 0 {
            String::new()
        } else {
            "<deep-inner name=\"d\"/>".to_owned()
        };
        let declaration = Declaration::new(if N == 3 { "deep" } else { "deep-inner" });
        let declaration = match N {
            3 => declaration.uses::<Deep<2>>(),
            2 => declaration.uses::<Deep<1>>(),
            1 => declaration.uses::<Deep<0>>(),
            _ => declaration,
        };
        declaration.template(format!(
            "<mujoco><worldbody>{}{inner}{}</worldbody></mujoco>",
            "<body>".repeat(200),
            "</body>".repeat(200)
        ))
    }
}

#[test]
fn worlds_nested_too_deep_stop_with_an_error() {
    let error = error_of::<Deep<3>>();
    assert_eq!(error.component, "/d/d");
    assert_eq!(error.element.as_deref(), Some("body"));
    assert_eq!(
        error.message,
        "the composed world nests elements deeper than 512"
    );
    let deep = compose::<Deep<1>>().expect("400 levels compose");
    let xml = deep.mjcf.to_xml();
    assert_eq!(xml.matches("<body").count(), 400);
    let parsed = yarok_core::template::xml::Element::parse(&xml);
    assert!(
        parsed.is_err(),
        "the XML parser still refuses 400 levels in one template"
    );
}
