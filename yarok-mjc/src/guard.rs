//! MJCF that makes MuJoCo 4.0.1 end the process instead of reporting an error, refused before
//! MuJoCo sees it.
//!
//! Found by loading every MJCF element, without attributes, in every section: only
//! `<asset><model/></asset>` (no `file`) aborts (an uncaught C++ `bad_optional_access`).

use yarok_core::template::xml::Element;

use crate::error::ModelError;

/// Refuses `xml` when it holds an input known to abort MuJoCo; text that does not parse is left
/// to MuJoCo, which reports it.
pub(crate) fn refuse_known_aborts(xml: &str, origin: &str) -> Result<(), ModelError> {
    let Ok(document) = Element::parse(xml) else {
        return Ok(());
    };
    match known_abort(&document.root) {
        Some((element, problem)) => Err(ModelError::Compile {
            origin: origin.to_owned(),
            message: format!(
                "line {}, column {}: {problem}",
                element.position.line, element.position.column
            ),
        }),
        None => Ok(()),
    }
}

/// The first element of `root` known to abort MuJoCo, and why.
pub(crate) fn known_abort(root: &Element) -> Option<(&Element, &'static str)> {
    root.children
        .iter()
        .filter(|s| s.name == "asset")
        .flat_map(|asset| &asset.children)
        .find(|e| e.name == "model" && e.attribute("file").is_none())
        .map(|model| (model, "<model> in <asset> needs a `file`"))
}
