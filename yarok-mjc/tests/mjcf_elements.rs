//! The composer's list of MJCF element names agrees with MuJoCo: MuJoCo recognises every name
//! on it in some section, and refuses a name that is not on it.

use yarok_core::compose::MJCF_ELEMENTS;
use yarok_mjc::Model;

/// Where each element can appear, as a document with `{}` where the element goes.
const PLACES: [&str; 26] = [
    "<mujoco>{}</mujoco>",
    "<mujoco><worldbody>{}</worldbody></mujoco>",
    "<mujoco><worldbody><body>{}</body></worldbody></mujoco>",
    "<mujoco><asset>{}</asset></mujoco>",
    "<mujoco><asset><mesh name='m' vertex='0 0 0 1 0 0 0 1 0 0 0 1'>{}</mesh></asset></mujoco>",
    "<mujoco><asset><material name='m'>{}</material></asset></mujoco>",
    "<mujoco><actuator>{}</actuator></mujoco>",
    "<mujoco><sensor>{}</sensor></mujoco>",
    "<mujoco><equality>{}</equality></mujoco>",
    "<mujoco><tendon>{}</tendon></mujoco>",
    "<mujoco><tendon><spatial>{}</spatial></tendon></mujoco>",
    "<mujoco><contact>{}</contact></mujoco>",
    "<mujoco><keyframe>{}</keyframe></mujoco>",
    "<mujoco><visual>{}</visual></mujoco>",
    "<mujoco><default>{}</default></mujoco>",
    "<mujoco><custom>{}</custom></mujoco>",
    "<mujoco><custom><tuple name='t'>{}</tuple></custom></mujoco>",
    "<mujoco><extension>{}</extension></mujoco>",
    "<mujoco><extension><plugin plugin='p'>{}</plugin></extension></mujoco>",
    "<mujoco><deformable>{}</deformable></mujoco>",
    "<mujoco><option>{}</option></mujoco>",
    "<mujoco><compiler>{}</compiler></mujoco>",
    "<mujoco><worldbody><flexcomp>{}</flexcomp></worldbody></mujoco>",
    "<mujoco><worldbody><body><plugin>{}</plugin></body></worldbody></mujoco>",
    "<mujoco><deformable><skin>{}</skin></deformable></mujoco>",
    "<mujoco><deformable><flex>{}</flex></deformable></mujoco>",
];

fn recognised(name: &str) -> bool {
    if name == "mujoco" {
        return Model::from_xml_str("<mujoco/>").is_ok();
    }
    PLACES.iter().any(|place| {
        let xml = place.replace("{}", &format!("<{name}/>"));
        match Model::from_xml_str(&xml) {
            Ok(_) => true,
            Err(error) => !error.to_string().contains("unrecognized element"),
        }
    })
}

#[test]
fn mujoco_recognises_every_listed_element() {
    let unknown: Vec<&str> = MJCF_ELEMENTS
        .iter()
        .copied()
        .filter(|name| !recognised(name))
        .collect();
    assert!(unknown.is_empty(), "MuJoCo does not know {unknown:?}");
    assert!(
        MJCF_ELEMENTS.is_sorted_by_key(|name| (name.len(), *name)),
        "the list is searched by bisection, by length then text"
    );
}

#[test]
fn names_off_the_list_are_refused_by_mujoco_too() {
    for name in ["arm3", "composite", "bogus", "bodyy"] {
        assert!(!MJCF_ELEMENTS.contains(&name));
        assert!(!recognised(name), "MuJoCo knows <{name}>");
    }
}

/// The one element that, written bare, makes MuJoCo 4.0.1 abort the process is refused first.
#[test]
fn an_asset_model_without_a_file_is_an_error_not_an_abort() {
    let error = Model::from_xml_str("<mujoco>\n<asset>\n  <model name='m'/>\n</asset></mujoco>")
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "MuJoCo cannot load <string>: line 3, column 3: <model> in <asset> needs a `file`"
    );
}
