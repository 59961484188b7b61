//! Components in components: paths, nesting with `parent=`, `extends`, merged sections and
//! complete namespacing.

#[macro_use]
mod common;

use yarok_core::component::{Component, ComponentType, Declaration, NameKind};
use yarok_core::compose::{compose, compose_with};
use yarok_core::template::xml::Element;
use yarok_core::value::{Config, IntoValue, Overrides};

/// Every `(tag, attribute, value)` in the subtree, for asserting names and references.
fn attributes(element: &Element) -> Vec<(String, String, String)> {
    element
        .descendants()
        .into_iter()
        .flat_map(|e| {
            e.attributes
                .iter()
                .map(|a| (e.name.clone(), a.name.clone(), a.value.clone()))
        })
        .collect()
}

fn has(element: &Element, tag: &str, attribute: &str, value: &str) -> bool {
    attributes(element)
        .iter()
        .any(|(t, a, v)| t == tag && a == attribute && v == value)
}

component!(
    Finger,
    Declaration::new("finger").default("length", 0.04).template(
        r#"<mujoco>
             <default><default class="pad"><geom friction="2"/></default></default>
             <asset><material name="rubber" rgba="0 0 0 1"/></asset>
             <worldbody>
               <body name="link"><joint name="slide" type="slide"/>
                 <geom class="pad" material="rubber" size="0.01 0.01 {length}" type="box"/>
                 <site name="tip"/>
               </body>
             </worldbody>
             <tendon><spatial name="cable"><site site="tip"/><site site="/anchor"/></spatial></tendon>
             <equality><joint joint1="slide" joint2="/base_slide"/></equality>
             <contact><exclude body1="link" body2="/base"/><pair geom1="pad_geom" geom2="/ground"/></contact>
             <actuator><position name="push" joint="slide" class="pad"/></actuator>
             <sensor><touch name="touch" site="tip"/><framepos name="where" objtype="site" objname="tip" reftype="body" refname="link"/></sensor>
             <keyframe><key name="in" qpos="0.01"/></keyframe>
             <custom><numeric name="gain" data="2"/></custom>
           </mujoco>"#,
    )
);

component!(
    Hand,
    Declaration::new("hand").uses::<Finger>().template(
        r#"<mujoco><worldbody>
             <body name="palm">
               <finger name="left" length="0.05"/>
               <finger name="right"/>
             </body>
           </worldbody></mujoco>"#,
    )
);

component!(
    World,
    Declaration::new("world").uses::<Hand>().template(
        r#"<mujoco model="lab">
             <worldbody>
               <geom name="ground" type="plane" size="1 1 1"/>
               <site name="anchor"/>
               <body name="base"><joint name="base_slide" type="slide"/>
                 <hand name="hand">
                   <geom name="marker" size="0.01"/>
                   <site name="on_left" parent="palm"/>
                 </hand>
               </body>
             </worldbody>
           </mujoco>"#,
    )
);

#[test]
fn paths_and_names_follow_nesting_and_each_copy_is_namespaced() {
    let world = compose::<World>().unwrap();
    let paths: Vec<&str> = world.instances.iter().map(|i| i.path.as_str()).collect();
    assert_eq!(paths, ["/", "/hand", "/hand/left", "/hand/right"]);
    let mjcf = &world.mjcf;
    assert_eq!(mjcf.attribute("model"), Some("lab"));
    // The world's names stay as written.
    for name in ["ground", "anchor", "base", "marker", "on_left"] {
        assert!(
            attributes(mjcf)
                .iter()
                .any(|(_, a, v)| a == "name" && v == name),
            "{name}"
        );
    }
    for side in ["left", "right"] {
        let p = format!("hand/{side}/");
        let expected = [
            ("body", "name", format!("{p}link")),
            ("joint", "name", format!("{p}slide")),
            ("geom", "class", format!("{p}pad")),
            ("geom", "material", format!("{p}rubber")),
            ("material", "name", format!("{p}rubber")),
            ("default", "class", format!("{p}pad")),
            ("default", "class", format!("{p}main")),
            ("body", "childclass", format!("{p}main")),
            ("spatial", "name", format!("{p}cable")),
            ("site", "site", format!("{p}tip")),
            ("joint", "joint1", format!("{p}slide")),
            ("exclude", "body1", format!("{p}link")),
            ("pair", "geom1", format!("{p}pad_geom")),
            ("position", "joint", format!("{p}slide")),
            ("position", "class", format!("{p}pad")),
            ("touch", "site", format!("{p}tip")),
            ("framepos", "objname", format!("{p}tip")),
            ("framepos", "refname", format!("{p}link")),
            ("numeric", "name", format!("{p}gain")),
        ];
        for (tag, attribute, value) in expected {
            assert!(
                has(mjcf, tag, attribute, &value),
                "missing <{tag} {attribute}=\"{value}\">\n{}",
                world.to_xml()
            );
        }
    }
    // References with a leading `/` name the world's objects.
    assert!(has(mjcf, "site", "site", "anchor"));
    assert!(has(mjcf, "joint", "joint2", "base_slide"));
    assert!(has(mjcf, "exclude", "body2", "base"));
    assert!(has(mjcf, "pair", "geom2", "ground"));
    // Config from the tag reached the template.
    assert!(has(mjcf, "geom", "size", "0.01 0.01 0.05"));
    assert!(has(mjcf, "geom", "size", "0.01 0.01 0.04"));
    // Keyframes are lifted out, named per copy.
    assert!(mjcf.child("keyframe").is_none());
    let keys: Vec<&str> = world.keyframes.iter().map(|k| k.name.as_str()).collect();
    assert_eq!(keys, ["hand/left/in", "hand/right/in"]);
    let left = world.instance("/hand/left").unwrap();
    assert_eq!(left.names.get(NameKind::Site, "tip"), Some("hand/left/tip"));
    assert_eq!(
        left.names.get(NameKind::Keyframe, "in"),
        Some("hand/left/in")
    );
    assert_eq!(
        left.names.get(NameKind::Actuator, "push"),
        Some("hand/left/push")
    );
    assert_eq!(left.joints, [1]);
    assert_eq!(world.instance("/").unwrap().joints, [0]);
}

#[test]
fn nested_content_goes_in_place_or_into_the_named_body() {
    let world = compose::<World>().unwrap();
    let base = &world.mjcf.child("worldbody").unwrap().children[2];
    let order: Vec<&str> = base
        .children
        .iter()
        .map(|c| c.attribute("name").unwrap_or(&c.name))
        .collect();
    assert_eq!(order, ["base_slide", "hand/palm", "marker"]);
    let palm = &base.children[1];
    let palm_children: Vec<&str> = palm
        .children
        .iter()
        .filter_map(|c| c.attribute("name"))
        .collect();
    assert_eq!(
        palm_children,
        ["hand/left/link", "hand/right/link", "on_left"]
    );
}

#[test]
fn sub_component_defaults_become_its_own_class_inside_the_world_default() {
    let world = compose::<World>().unwrap();
    let defaults = world.mjcf.child("default").unwrap();
    assert_eq!(
        defaults.attribute("class"),
        None,
        "the world's default stays `main`"
    );
    let classes: Vec<&str> = defaults
        .children
        .iter()
        .filter_map(|d| d.attribute("class"))
        .collect();
    assert_eq!(classes, ["hand/left/main", "hand/right/main"]);
    assert_eq!(
        defaults.children[0].children[0].attribute("class"),
        Some("hand/left/pad")
    );
}

component!(
    Gripper,
    Declaration::new("gripper")
        .template(r#"<mujoco><worldbody><body name="palm"/></worldbody></mujoco>"#)
);

component!(
    Arm,
    Declaration::new("arm").template(
        r#"<mujoco><worldbody><body name="base"><body name="flange"/></body></worldbody></mujoco>"#
    )
);

component!(
    Cell,
    Declaration::new("cell")
        .uses::<Arm>()
        .uses::<Gripper>()
        .template(
            r#"<mujoco><worldbody>
             <arm name="arm"><gripper name="gripper" parent="flange"/></arm>
           </worldbody>
           <equality><weld body1="arm/flange" body2="arm/gripper/palm"/></equality></mujoco>"#,
        )
);

#[test]
fn a_component_inside_a_component_tag_is_its_child_and_can_be_referenced_by_path() {
    let world = compose::<Cell>().unwrap();
    let paths: Vec<&str> = world.instances.iter().map(|i| i.path.as_str()).collect();
    assert_eq!(paths, ["/", "/arm", "/arm/gripper"]);
    let flange = &world.mjcf.child("worldbody").unwrap().children[0].children[0];
    assert_eq!(flange.attribute("name"), Some("arm/flange"));
    assert_eq!(
        flange.children[0].attribute("name"),
        Some("arm/gripper/palm")
    );
    assert!(has(&world.mjcf, "weld", "body2", "arm/gripper/palm"));
}

component!(
    Base,
    Declaration::new("base").default("size", 1).template(
        r#"<mujoco>
             <compiler angle="radian"/>
             <asset><material name="grid"/></asset>
             <worldbody><geom name="floor" type="plane" size="{size} {size} 1" material="grid"/></worldbody>
           </mujoco>"#,
    )
);

component!(
    Derived,
    Declaration::new("derived")
        .extends::<Base>()
        .default("size", 3)
        .template(
            r#"<mujoco>
             <option timestep="0.001"/>
             <worldbody><geom name="rug" material="grid" size="{size}"/></worldbody>
           </mujoco>"#,
        )
);

component!(Room, Declaration::new("room").uses::<Derived>().template(
    r#"<mujoco><compiler angle="radian"/><option timestep="0.001"/><worldbody><derived name="a"/><derived name="b" size="2"/></worldbody></mujoco>"#
));

#[test]
fn extends_merges_the_base_with_one_prefix_and_the_child_sees_base_names() {
    let world = compose::<Derived>().unwrap();
    let xml = world.to_xml();
    assert!(has(&world.mjcf, "geom", "material", "grid"), "{xml}");
    assert!(
        has(&world.mjcf, "geom", "size", "3 3 1"),
        "the child's default wins: {xml}"
    );
    assert!(has(&world.mjcf, "option", "timestep", "0.001"));
    assert!(has(&world.mjcf, "compiler", "angle", "radian"));

    let room = compose::<Room>().unwrap();
    for (prefix, size) in [("a/", "3"), ("b/", "2")] {
        assert!(has(&room.mjcf, "geom", "name", &format!("{prefix}floor")));
        assert!(has(
            &room.mjcf,
            "geom",
            "material",
            &format!("{prefix}grid")
        ));
        assert!(has(&room.mjcf, "geom", "size", size));
    }
    assert_eq!(
        room.mjcf.child("option").unwrap().attribute("timestep"),
        Some("0.001"),
        "equal settings merge"
    );
}

component!(
    Gravityless,
    Declaration::new("gravityless").template(
        r#"<mujoco>
             <option gravity="0 0 0"/>
             <worldbody><geom name="g" size="1"/></worldbody>
           </mujoco>"#
    )
);
component!(
    Upside,
    Declaration::new("upside").template(
        r#"<mujoco>
             <compiler eulerseq="zyx"/>
             <worldbody><body name="b" euler="0 0 1"/></worldbody>
           </mujoco>"#
    )
);
component!(
    Weighed,
    Declaration::new("weighed").template(
        r#"<mujoco>
             <compiler settotalmass="5"/>
             <worldbody><body name="b"><geom size="1"/></body></worldbody>
           </mujoco>"#
    )
);
component!(
    Unflagged,
    Declaration::new("unflagged").template(
        r#"<mujoco>
             <option><flag gravity="disable"/></option>
             <worldbody><geom name="g" size="1"/></worldbody>
           </mujoco>"#
    )
);
component!(
    Solver,
    Declaration::new("solver").template(
        r#"<mujoco><option integrator="implicitfast" cone="elliptic"/><worldbody/></mujoco>"#
    )
);
/// A world holding one `C` named `c`.
struct Lab<C>(std::marker::PhantomData<C>);

impl<C: Component> Component for Lab<C> {
    fn declaration() -> Declaration {
        let tag = C::declaration().tag().to_owned();
        Declaration::new("lab").uses::<C>().template(format!(
            r#"<mujoco><worldbody><body name="floor"/><{tag} name="c"/></worldbody></mujoco>"#
        ))
    }
}

/// A wrapped component's settings that MuJoCo applies to every body (gravity, the time step, a
/// physics flag, how Euler angles are read, a total mass) would silently change the whole
/// world, the world's own bodies included: each is refused at its attribute, saying why and
/// what to do. The world may set them, and a component may then agree; a component's solver
/// choices are taken.
#[test]
fn a_component_cannot_change_the_whole_worlds_physics() {
    for (error, attribute, why) in [
        (
            compose::<Lab<Gravityless>>(),
            "gravity",
            "physical constants",
        ),
        (compose::<Lab<Upside>>(), "eulerseq", "Euler angle"),
        (
            compose::<Lab<Weighed>>(),
            "settotalmass",
            "masses and inertias",
        ),
        (compose::<Lab<Unflagged>>(), "gravity", "flag"),
    ] {
        let error = error.unwrap_err();
        assert_eq!(error.component, "/c", "{error}");
        assert_eq!(error.attribute.as_deref(), Some(attribute), "{error}");
        assert!(
            error.message.contains("would change the whole world")
                && error.message.contains(why)
                && error.message.contains("world's template"),
            "{error}"
        );
        assert!(error.position.is_some(), "{error}");
    }
    let solver = compose::<Lab<Solver>>().unwrap();
    assert!(has(&solver.mjcf, "option", "integrator", "implicitfast"));
}

component!(
    Fast,
    Declaration::new("fast").template(r#"<mujoco><option timestep="0.001"/><worldbody/></mujoco>"#)
);
component!(
    Slow,
    Declaration::new("slow").uses::<Fast>().template(
        r#"<mujoco><option timestep="0.002"/><worldbody><fast name="f"/></worldbody></mujoco>"#
    )
);

#[test]
fn conflicting_global_settings_are_an_error_naming_both_components() {
    let error = compose::<Slow>().unwrap_err();
    assert_eq!(error.component, "/f");
    assert_eq!(error.attribute.as_deref(), Some("timestep"));
    assert!(
        error.message.contains("\"0.001\" here but \"0.002\" in /"),
        "{error}"
    );
}

component!(
    Radians,
    Declaration::new("radians").template(
        r#"<mujoco><compiler angle="radian"/><worldbody><body name="b" euler="0 0 3.141592653589793"><joint name="j" range="-1.5707963267948966 0"/></body></worldbody></mujoco>"#
    )
);
component!(
    Degrees,
    Declaration::new("degrees").uses::<Radians>().template(
        r#"<mujoco><worldbody><body name="d" euler="0 0 90"/><radians name="r"/></worldbody></mujoco>"#
    )
);

#[test]
fn components_writing_angles_in_another_unit_are_converted_to_the_worlds() {
    let world = compose::<Degrees>().unwrap();
    assert!(
        has(&world.mjcf, "body", "euler", "0 0 180"),
        "{}",
        world.to_xml()
    );
    assert!(
        has(&world.mjcf, "joint", "range", "-90 0"),
        "{}",
        world.to_xml()
    );
    assert!(
        has(&world.mjcf, "body", "euler", "0 0 90"),
        "the world's own angles stay"
    );
    assert!(
        !world.to_xml().contains("radian"),
        "one unit for the whole model: {}",
        world.to_xml()
    );
}

#[test]
fn config_is_typed_and_unknown_keys_and_paths_are_errors_with_suggestions() {
    let overrides = Overrides::from([("/hand/left".to_owned(), Config::from([("length", 0.07)]))]);
    let world = compose_with(ComponentType::of::<World>(), &overrides).unwrap();
    assert_eq!(
        world.instance("/hand/left").unwrap().config.get("length"),
        Some(&0.07.into_value())
    );
    assert!(has(&world.mjcf, "geom", "size", "0.01 0.01 0.07"));

    let overrides = Overrides::from([("/hand/left".to_owned(), Config::from([("lenght", 0.07)]))]);
    let error = compose_with(ComponentType::of::<World>(), &overrides).unwrap_err();
    assert!(
        error.message.contains("no config key `lenght`")
            && error.message.contains("did you mean `length`?"),
        "{error}"
    );

    let overrides = Overrides::from([("/hand/lft".to_owned(), Config::from([("length", 0.07)]))]);
    let error = compose_with(ComponentType::of::<World>(), &overrides).unwrap_err();
    assert!(
        error.message.contains("/hand/lft") && error.message.contains("did you mean `/hand/left`?"),
        "{error}"
    );

    let overrides =
        Overrides::from([("/hand/left".to_owned(), Config::from([("length", "long")]))]);
    let error = compose_with(ComponentType::of::<World>(), &overrides).unwrap_err();
    assert!(
        error.message.contains("`length` expects a number"),
        "{error}"
    );
}
