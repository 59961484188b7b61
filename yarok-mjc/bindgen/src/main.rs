//! Writes the raw MuJoCo bindings: `yarok-mjc-bindgen INCLUDE_DIR OUTPUT.rs`.
//!
//! Functions become fields of a `MuJoCo` struct loaded with libloading (bindgen's dynamic
//! loading), so that the library is opened at run time from a known path and no binary needs an
//! rpath. Global variables (legacy handlers, callbacks) are left out: yarok does not use them.

use std::path::PathBuf;

fn main() {
    let mut args = std::env::args_os().skip(1);
    let (Some(include), Some(output)) = (args.next(), args.next()) else {
        eprintln!("usage: yarok-mjc-bindgen INCLUDE_DIR OUTPUT.rs");
        std::process::exit(2);
    };
    let include = PathBuf::from(include);
    let bindings = bindgen::Builder::default()
        .header(include.join("mujoco/mujoco.h").to_string_lossy())
        .clang_arg(format!("-I{}", include.display()))
        .allowlist_function("mj.*")
        .allowlist_type("mj.*")
        .allowlist_var("mj.*")
        .blocklist_item("mju_user_.*|mjcb_.*|mjCOLLISIONFUNC|mj[A-Z]+STRING")
        .dynamic_library_name("MuJoCo")
        .dynamic_link_require_all(true)
        .default_enum_style(bindgen::EnumVariation::Consts)
        .prepend_enum_name(false)
        .derive_default(true)
        .layout_tests(false)
        .generate_comments(true)
        .generate()
        .expect("bindgen failed on the MuJoCo headers");
    bindings.write_to_file(&output).expect("could not write the bindings");
}
