//! Errors name the component path, the template, line:column, element, attribute and expression.

use yarok_core::component::{Component, Declaration};
use yarok_core::compose::{ComposeError, compose};

macro_rules! component {
    ($name:ident, $template:expr) => {
        component!($name, $template, );
    };
    ($name:ident, $template:expr, $($uses:ident),*) => {
        struct $name;
        impl Component for $name {
            fn declaration() -> Declaration {
                Declaration::new(stringify!($name).to_lowercase()).default("n", 2)$(.uses::<$uses>())*.template($template)
            }
        }
    };
}

fn error_of<C: Component>() -> ComposeError {
    compose::<C>().expect_err("composition should fail")
}

fn at(error: &ComposeError) -> (u32, u32) {
    error
        .position
        .map(|p| (p.line, p.column))
        .expect("a position")
}

component!(
    Part,
    "<mujoco>\n  <worldbody>\n    <geom name=\"g\" size=\"{n / (n - 2)}\"/>\n  </worldbody>\n</mujoco>"
);
component!(
    Holder,
    "<mujoco><worldbody>\n<part name=\"p\"/></worldbody></mujoco>",
    Part
);

#[test]
fn an_expression_error_says_everything_about_where() {
    let error = error_of::<Holder>();
    assert_eq!(error.component, "/p");
    assert_eq!(error.template, "<part> (inline template)");
    assert_eq!(at(&error), (3, 20));
    assert_eq!(error.element.as_deref(), Some("geom"));
    assert_eq!(error.attribute.as_deref(), Some("size"));
    assert_eq!(error.expression.as_deref(), Some("n / (n - 2)"));
    assert_eq!(error.message, "division by zero");
    assert_eq!(
        error.to_string(),
        "component /p, <part> (inline template):3:20, <geom> attribute `size` expression `n / (n - 2)`: division by zero"
    );
}

component!(
    Unknown,
    "<mujoco><worldbody><geom size=\"{radius}\"/></worldbody></mujoco>"
);
component!(
    Syntax,
    "<mujoco><worldbody><geom size=\"{1 +}\"/></worldbody></mujoco>"
);
component!(
    Unclosed,
    "<mujoco><worldbody><geom size=\"{1 + 2\"/></worldbody></mujoco>"
);

#[test]
fn expression_messages_are_the_real_ones() {
    assert_eq!(
        error_of::<Unknown>().message,
        "name `radius` is not defined"
    );
    assert_eq!(
        error_of::<Syntax>().message,
        "unexpected end of expression (at character 4)"
    );
    assert_eq!(
        error_of::<Unclosed>().message,
        "unclosed `{` at character 1"
    );
}

component!(
    Broken,
    "<mujoco>\n<worldbody>\n  <body>\n</worldbody>\n</mujoco>"
);
component!(NotMjcf, "<robot/>");

#[test]
fn malformed_templates_name_the_line() {
    let error = error_of::<Broken>();
    assert_eq!(error.template, "<broken> (inline template)");
    assert_eq!(error.position.unwrap().line, 4, "{error}");
    assert!(error_of::<NotMjcf>().message.contains("not <mujoco>"));
}

component!(
    Fine,
    "<mujoco><worldbody><body name=\"palm2\"/></worldbody></mujoco>"
);
component!(
    Nameless,
    "<mujoco><worldbody><fine/></worldbody></mujoco>",
    Fine
);
component!(
    Twice,
    "<mujoco><worldbody><fine name=\"p\"/><fine name=\"p\"/></worldbody></mujoco>",
    Fine
);
component!(
    Slash,
    "<mujoco><worldbody><fine name=\"a/b\"/></worldbody></mujoco>",
    Fine
);
component!(
    Outside,
    "<mujoco><asset><fine name=\"p\"/></asset><worldbody/></mujoco>",
    Fine
);
component!(
    Lost,
    "<mujoco><worldbody><fine name=\"h\"><site parent=\"palm\"/></fine></worldbody></mujoco>",
    Fine
);
component!(
    Stray,
    "<mujoco><worldbody><site parent=\"x\"/></worldbody></mujoco>"
);
component!(
    StrayComponent,
    "<mujoco><worldbody><body name=\"b\"/><fine name=\"f\" parent=\"b\"/></worldbody></mujoco>",
    Fine
);
component!(
    Astray,
    "<mujoco><worldbody><fine name=\"h\"><site parent=\"zzz\"/></fine></worldbody></mujoco>",
    Fine
);
component!(
    Loop,
    "<mujoco><worldbody><for each=\"range(2)\"><geom/></for></worldbody></mujoco>"
);
component!(
    BadLoopName,
    "<mujoco><worldbody><for each=\"range(2)\" as=\"1x\"><geom/></for></worldbody></mujoco>"
);
component!(
    BadAngleUnit,
    "<mujoco><compiler angle=\"Degree\"/><worldbody><geom size=\"1\"/></worldbody></mujoco>"
);
component!(
    NotIterable,
    "<mujoco><worldbody><for each=\"n\" as=\"i\"><geom/></for></worldbody></mujoco>"
);
component!(
    BadKey,
    "<mujoco><worldbody><fine name=\"p\" m=\"1\"/></worldbody></mujoco>",
    Fine
);

#[test]
fn structural_mistakes_are_explained() {
    let cases = [
        (error_of::<Nameless>(), "a component tag needs a `name`"),
        (error_of::<Twice>(), "a component named /p already exists"),
        (error_of::<Slash>(), "\"a/b\" is not a valid component name"),
        (
            error_of::<Outside>(),
            "component tags belong in <worldbody>",
        ),
        (
            error_of::<Lost>(),
            "/h has no body or site named \"palm\"; did you mean `palm2`?",
        ),
        (
            error_of::<Stray>(),
            "`parent` places an element written directly inside a component tag \
             (<arm><site parent=\"wrist\"/></arm>) on that component's body or site; this \
             <site> is not",
        ),
        (
            error_of::<StrayComponent>(),
            "`parent` places an element written directly inside a component tag \
             (<arm><fine parent=\"wrist\"/></arm>) on that component's body or site; this \
             <fine> is not",
        ),
        (
            error_of::<Astray>(),
            "/h has no body or site named \"zzz\"; it has `palm2`",
        ),
        (error_of::<Loop>(), "<for> needs a `as` attribute"),
        (error_of::<NotIterable>(), "cannot loop over 2"),
        (
            error_of::<BadAngleUnit>(),
            "angle must be \"degree\" or \"radian\", as MuJoCo reads it, not \"Degree\"",
        ),
        (
            error_of::<BadLoopName>(),
            "`as` names the loop's variable: \"1x\" is not a name (letters, digits and _, not \
             starting with a digit, not a keyword)",
        ),
        (
            error_of::<BadKey>(),
            "no config key `m` (it has n); did you mean `n`?",
        ),
    ];
    for (error, message) in cases {
        assert_eq!(error.message, message, "{error}");
        assert!(error.position.is_some(), "{error}");
    }
}

#[test]
fn a_parent_error_names_the_element_that_carries_the_attribute() {
    let error = error_of::<Lost>();
    assert_eq!(error.element.as_deref(), Some("site"));
    assert_eq!(error.attribute.as_deref(), Some("parent"));
    assert_eq!(at(&error), (1, 41));
}

struct FromFile;
impl Component for FromFile {
    fn declaration() -> Declaration {
        Declaration::new("from_file").template_file("/nonexistent/template.xml")
    }
}

#[test]
fn an_unreadable_template_file_is_named() {
    let error = error_of::<FromFile>();
    assert_eq!(error.template, "/nonexistent/template.xml");
    assert!(
        error.message.starts_with("cannot read the template"),
        "{error}"
    );
}

component!(
    Huge,
    "<mujoco><worldbody><for each=\"range(1000)\" as=\"i\"><for each=\"range(1001)\" as=\"j\"><geom/></for></for></worldbody></mujoco>"
);

#[test]
fn templates_cannot_exhaust_memory_or_stack() {
    assert_eq!(
        error_of::<Huge>().message,
        "the world expands to more than 1000000 elements"
    );
    let deep = format!(
        "<mujoco><worldbody>{}{}</worldbody></mujoco>",
        "<body>".repeat(300),
        "</body>".repeat(300)
    );
    let error = yarok_core::template::xml::Element::parse(&deep).unwrap_err();
    assert_eq!(error.message, "elements nested deeper than 256");
}

component!(
    Peg,
    "<mujoco><worldbody><geom size=\"0.1\"/></worldbody></mujoco>"
);
component!(
    Typo,
    "<mujoco><worldbody>\n  <body name=\"b\">\n    <peg name=\"p\"/>\n    <pegs name=\"q\"/>\n  </body>\n</worldbody></mujoco>",
    Peg
);

#[test]
fn an_unknown_tag_is_refused_with_a_suggestion() {
    let error = error_of::<Typo>();
    assert_eq!(error.component, "/");
    assert_eq!(at(&error), (4, 5));
    assert_eq!(error.element.as_deref(), Some("pegs"));
    assert_eq!(
        error.message,
        "<pegs> is neither an MJCF element nor a component tag (<typo> uses <peg>); did you mean `peg`?"
    );
}

/// `fn main() -> Result<(), Box<dyn Error>>` prints a returned error with `{:?}`: the readable
/// message, with any cause it does not already include, not a dump of fields.
#[test]
fn errors_returned_from_main_print_their_message() {
    let boxed: Box<dyn std::error::Error> = Box::new(error_of::<Holder>());
    assert_eq!(format!("{boxed:?}"), boxed.to_string());
    assert!(!format!("{boxed:?}").contains("ErrorDetails"));
    let runtime: Box<dyn std::error::Error> = Box::new(yarok_core::runtime::RuntimeError::Compose(
        error_of::<Holder>(),
    ));
    assert_eq!(
        format!("{runtime:?}"),
        "component /p, <part> (inline template):3:20, <geom> attribute `size` expression `n / (n - 2)`: division by zero"
    );
}
