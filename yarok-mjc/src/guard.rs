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
    let Ok(root) = Element::parse(xml) else {
        return Ok(());
    };
    let assets = root.children.iter().filter(|s| s.name == "asset");
    let fileless = assets
        .flat_map(|asset| &asset.children)
        .find(|e| e.name == "model" && e.attribute("file").is_none());
    match fileless {
        Some(model) => Err(ModelError::Compile {
            origin: origin.to_owned(),
            message: format!(
                "line {}, column {}: <model> in <asset> needs a `file`",
                model.position.line, model.position.column
            ),
        }),
        None => Ok(()),
    }
}
