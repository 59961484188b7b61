//! Asset files and wrapped MJCF files: paths resolve against the component that names them.

#[macro_use]
mod common;

use std::path::{Path, PathBuf};

use yarok_core::component::Declaration;
use yarok_core::compose::compose;
use yarok_core::template::xml::Element;

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/robot")
}

fn find<'a>(root: &'a Element, tag: &str) -> Vec<&'a Element> {
    root.descendants()
        .into_iter()
        .filter(|e| e.name == tag)
        .collect()
}

component!(
    Robot,
    Declaration::new("robot").mjcf_file(fixtures().join("robot.xml"))
);
component!(
    Lab,
    Declaration::new("lab").uses::<Robot>().template(
        r#"<mujoco><compiler angle="radian"/><worldbody>
             <robot name="r1"/>
             <body name="shelf" pos="1 0 0"><robot name="r2"/></body>
           </worldbody></mujoco>"#
    )
);

#[test]
fn a_wrapped_model_keeps_its_assets_and_is_namespaced_per_copy() {
    let world = compose::<Lab>().unwrap();
    let meshes = find(&world.mjcf, "mesh");
    assert_eq!(meshes.len(), 2);
    for (mesh, prefix) in meshes.iter().zip(["r1/", "r2/"]) {
        assert_eq!(
            mesh.attribute("name"),
            Some(format!("{prefix}part").as_str()),
            "named after its file"
        );
        assert_eq!(
            Path::new(mesh.attribute("file").unwrap()),
            fixtures().join("assets/part.obj")
        );
    }
    let textures = find(&world.mjcf, "texture");
    assert_eq!(
        Path::new(textures[0].attribute("file").unwrap()),
        fixtures().join("textures/skin.png")
    );
    assert_eq!(textures[0].attribute("name"), Some("r1/skin"));
    assert_eq!(
        find(&world.mjcf, "material")[1].attribute("texture"),
        Some("r2/skin")
    );
    assert_eq!(
        find(&world.mjcf, "geom")[1].attribute("mesh"),
        Some("r2/part")
    );
    assert_eq!(
        world.assets,
        [
            fixtures().join("assets/part.obj"),
            fixtures().join("textures/skin.png")
        ]
    );
    // meshdir/texturedir are spent; the include is inlined; braces are left alone.
    let compiler = world.mjcf.child("compiler").unwrap();
    assert_eq!(compiler.attribute("meshdir"), None);
    assert_eq!(find(&world.mjcf, "include").len(), 0);
    assert_eq!(find(&world.mjcf, "joint")[0].attribute("class"), None);
    assert!(world.to_xml().contains(r#"data="{not an expression}""#));
    let defaults = world.mjcf.child("default").unwrap();
    assert_eq!(defaults.children[0].attribute("class"), Some("r1/main"));
    assert_eq!(
        defaults.children[0].children[0].attribute("damping"),
        Some("0.1")
    );
}

component!(
    Loose,
    Declaration::new("loose")
        .template(r#"<mujoco><asset><mesh file="part.obj"/></asset><worldbody/></mujoco>"#)
);
component!(
    Anchored,
    Declaration::new("anchored")
        .asset_dir(fixtures().join("assets"))
        .template(r#"<mujoco><asset><mesh name="p" file="{'part' + '.obj'}"/></asset><worldbody/></mujoco>"#)
);
component!(
    Missing,
    Declaration::new("missing").asset_dir(fixtures()).template(
        "<mujoco>\n  <asset>\n    <mesh file=\"nowhere.stl\"/>\n  </asset>\n  <worldbody/>\n</mujoco>"
    )
);

#[test]
fn relative_files_need_an_asset_folder_and_must_exist() {
    let error = compose::<Loose>().unwrap_err();
    assert!(error.message.contains("no asset folder"), "{error}");
    let world = compose::<Anchored>().unwrap();
    assert_eq!(world.assets, [fixtures().join("assets/part.obj")]);
    let error = compose::<Missing>().unwrap_err();
    assert_eq!(error.attribute.as_deref(), Some("file"));
    assert_eq!(error.position.map(|p| (p.line, p.column)), Some((3, 11)));
    assert!(
        error.message.contains("nowhere.stl does not exist"),
        "{error}"
    );
}
