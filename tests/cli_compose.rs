//! `yarok compose` dumps composed MJCF from a bundled component or a template file.

mod support;
use support::yarok_binary;

use yarok_binary::{yarok, yarok_fails};
use yarok_test::assert_says;

#[test]
fn composes_a_bundled_component_with_overrides() {
    let (code, xml, _) = yarok(&["compose", "tumble-tower", "--set", "rows=2"]);
    assert_eq!(code, 0);
    assert_eq!(xml.matches("<freejoint/>").count(), 6);
    assert_says(
        &xml,
        &[r#"<body name="block_1_2" pos="0.58 0.5640000000000001 0.0915""#],
    );
}

#[test]
fn composes_a_template_file_using_bundled_components() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("world.xml");
    std::fs::write(
        &file,
        r#"<mujoco><compiler angle="radian"/><worldbody>
        <geom name="floor" type="plane" size="1 1 1"/>
        <tumble-tower name="tower" rows="1"/>
    </worldbody></mujoco>"#,
    )
    .unwrap();
    let out = dir.path().join("composed.xml");
    let (code, _, _) = yarok(&[
        "compose",
        file.to_str().unwrap(),
        "--set",
        "/tower/rows=3",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0);
    let xml = std::fs::read_to_string(&out).unwrap();
    assert!(
        xml.contains(r#"name="tower/block_2_0""#) && !xml.contains("block_3_0"),
        "{xml}"
    );
    assert!(xml.contains(r#"<geom name="floor""#));

    // Composed again over what it wrote: replaced. Over the user's template, the input: refused,
    // the template kept byte for byte.
    let (code, _, stderr) = yarok(&[
        "compose",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let template = std::fs::read(&file).unwrap();
    let (code, _, stderr) = yarok(&[
        "compose",
        file.to_str().unwrap(),
        "--out",
        file.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{stderr}");
    yarok_test::assert_says(
        &stderr,
        &[
            file.to_str().unwrap(),
            "is not a composed world yarok wrote",
        ],
    );
    assert_eq!(std::fs::read(&file).unwrap(), template);
}

#[test]
fn errors_exit_with_2_and_say_where() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.xml");
    std::fs::write(
        &file,
        "<mujoco>\n<worldbody>\n<geom size=\"{missing}\"/>\n</worldbody>\n</mujoco>",
    )
    .unwrap();
    let (code, _, stderr) = yarok(&["compose", file.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains(&format!("{}:3:7", file.display())),
        "{stderr}"
    );
    assert_says(&stderr, &["name `missing` is not defined"]);

    yarok_fails(
        &["compose", "tumble-tower", "--set", "rowz=2"],
        2,
        &["did you mean `rows`?"],
    );
    yarok_fails(&["compose", "no-such-world"], 2, &["tumble-tower"]);
}

#[test]
fn help_goes_to_stdout_and_succeeds() {
    for args in [
        &["--help"][..],
        &["-h"],
        &["compose", "--help"],
        &["tactile", "--help"],
        &["run", "--help"],
    ] {
        let (code, out, err) = yarok(args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(out.starts_with("usage: yarok run"), "{args:?}: {out}");
        assert!(out.contains("yarok compose"), "{args:?}: {out}");
        assert!(err.is_empty(), "{args:?}: {err}");
    }
    let (code, out, err) = yarok(&[]);
    assert_eq!((code, out.as_str()), (2, ""));
    assert_says(&err, &["usage: yarok run"]);
}

#[test]
fn a_bad_set_value_names_the_argument() {
    let (code, _, err) = yarok(&["compose", "tumble-tower", "--set", "rows=many"]);
    assert_eq!(code, 2);
    assert_eq!(
        err.trim(),
        "error: component /, --set rows=many attribute `rows`: `rows` expects an integer, got \"many\""
    );
}

/// An expression that gives NaN or an infinity is an error naming the template's line and
/// column, not a model with `nan` in it.
#[test]
fn an_expression_that_is_not_a_finite_number_is_an_error_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    for (expression, name) in [("0**-1", "power"), ("float('nan')", "nan")] {
        let file = dir.path().join(format!("{name}.xml"));
        std::fs::write(
            &file,
            format!(
                "<mujoco>\n<worldbody>\n<geom size=\"{{{expression}}}\"/>\n</worldbody>\n</mujoco>"
            ),
        )
        .unwrap();
        let (code, _, stderr) = yarok(&["compose", file.to_str().unwrap()]);
        assert_eq!(code, 2, "{stderr}");
        assert!(
            stderr.contains(&format!("{}:3:7", file.display())),
            "{stderr}"
        );
        assert_says(&stderr, &["not a finite number"]);
    }
}
