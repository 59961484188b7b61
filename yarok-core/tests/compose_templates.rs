//! The template language inside MJCF: `{expr}`, `${expr}`, `if=`, `<if the>`, `<for>`, in every
//! section, in document order, with config and loop variables.

#[macro_use]
mod common;

use yarok_core::component::Declaration;
use yarok_core::compose::{Composition, compose};
use yarok_core::template::xml::Element;

fn names(parent: &Element) -> Vec<String> {
    parent
        .children
        .iter()
        .map(|c| c.attribute("name").unwrap_or(&c.name).to_owned())
        .collect()
}

fn section<'a>(world: &'a Composition, name: &str) -> &'a Element {
    world
        .mjcf
        .child(name)
        .unwrap_or_else(|| panic!("no <{name}> in\n{}", world.to_xml()))
}

component!(
    Values,
    Declaration::new("values")
        .default("size", 0.1)
        .default("count", 3)
        .default("pos", vec![0.1, 0.2, 0.3])
        .default("visible", true)
        .template(
            r#"<mujoco>
                 <worldbody>
                   <geom name="a" size="{size / 10}" pos="{pos}" rgba="${[1, 0, 0, 1]}"/>
                   <geom name="b{count}" fromto="0 0 {size * 2} 0 0 {0.1 + 0.2}" contype="{visible}"/>
                   <geom name="c" size="{{literal}}"/>
                 </worldbody>
               </mujoco>"#
        )
);

#[test]
fn expressions_fill_attributes_with_round_trip_numbers_and_space_separated_lists() {
    let world = compose::<Values>().unwrap();
    let body = section(&world, "worldbody");
    let a = &body.children[0];
    assert_eq!(a.attribute("size"), Some("0.01"));
    assert_eq!(a.attribute("pos"), Some("0.1 0.2 0.3"));
    assert_eq!(a.attribute("rgba"), Some("1 0 0 1"));
    let b = &body.children[1];
    assert_eq!(b.attribute("name"), Some("b3"));
    assert_eq!(
        b.attribute("fromto"),
        Some("0 0 0.2 0 0 0.30000000000000004")
    );
    assert_eq!(
        b.attribute("fromto")
            .unwrap()
            .split(' ')
            .next_back()
            .unwrap()
            .parse::<f64>()
            .unwrap(),
        0.1 + 0.2
    );
    assert_eq!(b.attribute("contype"), Some("true"));
    assert_eq!(body.children[2].attribute("size"), Some("{literal}"));
}

component!(
    Order,
    Declaration::new("order")
        .default("n", 2)
        .default("extra", false)
        .template(
            r#"<mujoco>
             <asset>
               <for each="range(n)" as="i"><material name="m{i}"/></for>
               <material name="last"/>
             </asset>
             <worldbody>
               <geom name="first"/>
               <for each="range(n)" as="i">
                 <body name="row{i}">
                   <for each="['x', 'y']" as="axis">
                     <site name="s{i}{axis}" if="i > 0 or axis == 'y'"/>
                   </for>
                   <if the="i == n - 1"><geom name="top{i}"/></if>
                 </body>
               </for>
               <geom name="middle"/>
               <if the="extra"><geom name="never"/></if>
               <if the="not extra"><geom name="shown"/></if>
               <geom name="gone" if="extra"/>
               <geom name="last"/>
             </worldbody>
             <actuator>
               <for each="range(n)" as="i"><motor name="motor{i}" joint="j{i}" if="i != 0"/></for>
             </actuator>
           </mujoco>"#,
        )
);

#[test]
fn control_constructs_keep_document_order_in_every_section() {
    let world = compose::<Order>().unwrap();
    assert_eq!(names(section(&world, "asset")), ["m0", "m1", "last"]);
    let body = section(&world, "worldbody");
    assert_eq!(
        names(body),
        ["first", "row0", "row1", "middle", "shown", "last"]
    );
    assert_eq!(names(&body.children[1]), ["s0y"]);
    assert_eq!(names(&body.children[2]), ["s1x", "s1y", "top1"]);
    assert_eq!(names(section(&world, "actuator")), ["motor1"]);
    assert_eq!(
        section(&world, "actuator").children[0].attribute("joint"),
        Some("j1")
    );
}

component!(
    Loops,
    Declaration::new("loops")
        .default("rows", vec![1, 2])
        .template(
            r#"<mujoco><worldbody>
             <for each="rows" as="r">
               <for each="range(r)" as="c">
                 <if the="c % 2 == 0"><geom name="g{r}_{c}" size="{r + c * 0.5}"/></if>
               </for>
             </for>
           </worldbody></mujoco>"#,
        )
);

#[test]
fn loops_nest_and_inner_blocks_see_outer_loop_variables() {
    let world = compose::<Loops>().unwrap();
    let body = section(&world, "worldbody");
    assert_eq!(names(body), ["g1_0", "g2_0"]);
    assert_eq!(body.children[1].attribute("size"), Some("2"));
}

component!(
    Tower,
    Declaration::new("tower").default("rows", 2).template(
        r#"<mujoco><worldbody>
             <for each="range(rows)" as="z"><for each="range(3)" as="x">
               <body name="b{z}{x}" pos="{0.5 + 0.082*x if z % 2 == 0 else 0.58} {0.48 if z % 2 == 0 else 0.4 + 0.082*x} ${0.061*z}"/>
             </for></for>
           </worldbody></mujoco>"#,
    )
);

#[test]
fn the_original_readme_tower_expressions_work_verbatim() {
    let world = compose::<Tower>().unwrap();
    let body = section(&world, "worldbody");
    assert_eq!(body.children.len(), 6);
    assert_eq!(body.children[1].attribute("pos"), Some("0.582 0.48 0"));
    assert_eq!(
        body.children[5].attribute("pos"),
        Some("0.58 0.5640000000000001 0.061")
    );
}
