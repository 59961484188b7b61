//! Loading models: from strings with in-memory assets, from files with assets in subfolders,
//! MuJoCo's own errors, and the library version.

use std::fs;

use yarok_mjc::{Model, ModelError, ObjectKind, sys};

const TETRAHEDRON: &str =
    "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

fn mesh_scene(mesh_file: &str, compiler: &str) -> String {
    format!(
        r#"<mujoco>
             {compiler}
             <asset><mesh name="tetra" file="{mesh_file}"/></asset>
             <worldbody><body name="piece"><freejoint/><geom type="mesh" mesh="tetra"/></body></worldbody>
           </mujoco>"#
    )
}

fn assert_one_tetrahedron(model: &Model) {
    assert_eq!(model.ffi().nmesh, 1);
    assert_eq!(model.ffi().nmeshvert, 4);
    assert_eq!(model.count(ObjectKind::Geom), 1);
    assert_eq!(model.nq(), 7);
}

#[test]
fn library_version_matches_the_headers() {
    let header = sys::mjVERSION_HEADER;
    let expected = format!(
        "{}.{}.{}",
        header / 1_000_000,
        header / 1000 % 1000,
        header % 1000
    );
    assert_eq!(yarok_mjc::mujoco_version().unwrap(), expected);
    assert_eq!(expected, yarok_mjc::MUJOCO_VERSION);
}

#[test]
fn from_string_with_an_in_memory_mesh_in_a_subfolder() {
    let xml = mesh_scene("meshes/tetra.obj", "");
    let model = Model::from_xml_str_with_assets(&xml, [("meshes/tetra.obj", TETRAHEDRON)]).unwrap();
    assert_one_tetrahedron(&model);
}

#[test]
fn from_file_with_a_mesh_in_a_subfolder() {
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join("meshes")).unwrap();
    fs::write(dir.path().join("meshes/tetra.obj"), TETRAHEDRON).unwrap();
    fs::write(
        dir.path().join("scene.xml"),
        mesh_scene("meshes/tetra.obj", ""),
    )
    .unwrap();
    fs::write(
        dir.path().join("meshdir.xml"),
        mesh_scene("tetra.obj", r#"<compiler meshdir="meshes"/>"#),
    )
    .unwrap();

    assert_one_tetrahedron(&Model::from_file(dir.path().join("scene.xml")).unwrap());
    assert_one_tetrahedron(&Model::from_file(dir.path().join("meshdir.xml")).unwrap());
}

#[test]
fn malformed_xml_reports_mujocos_message() {
    let error = Model::from_xml_str("<mujoco><worldbody><body></worldbody></mujoco>").unwrap_err();
    let ModelError::Compile { origin, message } = &error else {
        panic!("{error:?}")
    };
    assert_eq!(origin, "<string>");
    assert!(message.contains("XML parse error"), "{message}");
    assert!(error.to_string().contains(message.as_str()));
}

#[test]
fn compile_error_reports_mujocos_message_with_the_element() {
    let error = Model::from_xml_str(
        r#"<mujoco><worldbody><geom type="box" fromto="0 0 0 1 0 0" size="0.1 0.1 0.1"/>
           <geom type="sphere" size="-1"/></worldbody></mujoco>"#,
    )
    .unwrap_err();
    let ModelError::Compile { message, .. } = error else {
        panic!("{error:?}")
    };
    assert!(message.contains("line 2"), "{message}");
}

#[test]
fn missing_file_and_missing_mesh_are_errors_naming_them() {
    let error = Model::from_file("/nonexistent/scene.xml").unwrap_err();
    assert!(
        error.to_string().contains("/nonexistent/scene.xml"),
        "{error}"
    );

    let error = Model::from_xml_str(&mesh_scene("meshes/absent.obj", "")).unwrap_err();
    assert!(error.to_string().contains("absent.obj"), "{error}");
}

#[test]
fn repeated_asset_name_is_an_error() {
    let xml = mesh_scene("meshes/tetra.obj", "");
    let error = Model::from_xml_str_with_assets(
        &xml,
        [
            ("meshes/tetra.obj", TETRAHEDRON),
            ("meshes/tetra.obj", TETRAHEDRON),
        ],
    )
    .unwrap_err();
    assert_eq!(
        error,
        ModelError::Asset {
            name: "meshes/tetra.obj".into(),
            reason: "repeated name"
        }
    );
}

#[test]
fn nul_bytes_are_rejected_before_reaching_mujoco() {
    let model = Model::from_xml_str("<mujoco/>").unwrap();
    assert!(matches!(
        model.body("a\0b"),
        Err(ModelError::InteriorNul { .. })
    ));
    let error = Model::from_xml_str_with_assets("<mujoco/>", [("a\0b", "")]).unwrap_err();
    assert!(matches!(error, ModelError::InteriorNul { .. }));
}
