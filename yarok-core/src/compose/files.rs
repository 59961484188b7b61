//! Asset files: `file=` attributes resolved against the folder of the component that wrote
//! them (and its `meshdir`/`texturedir`), and `<include>`s inlined.

use std::collections::BTreeSet;
use std::path::{Component, Path, PathBuf};

use super::error::Problem;
use super::limits::MAX_WORLD_DEPTH;
use crate::template::xml::{Element, Position};

/// Nested `<include>`s deeper than this are refused (a file including itself).
const MAX_INCLUDE_DEPTH: usize = 16;

/// A template's file-related facts.
pub(super) struct Origin {
    pub(super) label: String,
    dir: Option<PathBuf>,
    meshdir: Option<PathBuf>,
    texturedir: Option<PathBuf>,
}

impl Origin {
    pub(super) fn new(label: String, dir: Option<PathBuf>, tree: &Element) -> Self {
        let compiler = tree.child("compiler");
        let setting = |name: &str| compiler.and_then(|c| c.attribute(name)).map(PathBuf::from);
        let assetdir = setting("assetdir");
        let under = |sub: Option<PathBuf>| {
            let sub = sub.or_else(|| assetdir.clone());
            match (&dir, sub) {
                (Some(dir), Some(sub)) => Some(dir.join(sub)),
                (Some(dir), None) => Some(dir.clone()),
                (None, sub) => sub.filter(|s| s.is_absolute()),
            }
        };
        Self {
            meshdir: under(setting("meshdir")),
            texturedir: under(setting("texturedir")),
            dir,
            label,
        }
    }
}

/// Which folder each file attribute of each element resolves against.
fn file_attributes(tag: &str) -> &'static [&'static str] {
    match tag {
        "mesh" | "skin" | "hfield" => &["file"],
        "texture" => &[
            "file",
            "fileright",
            "fileleft",
            "fileup",
            "filedown",
            "filefront",
            "fileback",
        ],
        "model" => &["file"],
        _ => &[],
    }
}

/// Makes every asset path absolute and checks it exists; drops `meshdir`, `texturedir` and
/// `assetdir`, which no longer apply.
pub(super) fn resolve(
    elements: &mut [Element],
    origins: &[Origin],
    assets: &mut BTreeSet<PathBuf>,
) -> Result<(), Problem> {
    for element in elements {
        if element.name == "compiler" {
            element
                .attributes
                .retain(|a| !matches!(a.name.as_str(), "meshdir" | "texturedir" | "assetdir"));
        }
        name_after_file(element);
        let origin = &origins[element.origin];
        let base = if element.name == "texture" {
            &origin.texturedir
        } else if element.name == "model" {
            &origin.dir
        } else {
            &origin.meshdir
        };
        for index in 0..element.attributes.len() {
            if !file_attributes(&element.name).contains(&element.attributes[index].name.as_str()) {
                continue;
            }
            let written = PathBuf::from(&element.attributes[index].value);
            let path = match (written.is_absolute(), base) {
                (true, _) => written,
                (false, Some(base)) => normalize(&base.join(&written)),
                (false, None) => {
                    let message = format!(
                        "relative file {:?} in a component with no asset folder; give it `asset_dir` or a template file",
                        element.attributes[index].value
                    );
                    return Err(Box::new((
                        element.clone(),
                        Some(element.attributes[index].clone()),
                        message,
                    )));
                }
            };
            if !path.is_file() {
                let message = format!("file {} does not exist", path.display());
                return Err(Box::new((
                    element.clone(),
                    Some(element.attributes[index].clone()),
                    message,
                )));
            }
            element.attributes[index].value = path.display().to_string();
            assets.insert(path);
        }
        resolve(&mut element.children, origins, assets)?;
    }
    Ok(())
}

/// MuJoCo names an unnamed mesh, texture, height field or skin after its file (`parts/arm.stl` is
/// `arm`); the name is written out so that it can be namespaced like any other.
fn name_after_file(element: &mut Element) {
    if !matches!(
        element.name.as_str(),
        "mesh" | "texture" | "hfield" | "skin"
    ) || element.attribute("name").is_some()
    {
        return;
    }
    let stem = element
        .attribute("file")
        .and_then(|file| Path::new(file).file_stem())
        .map(|s| s.to_string_lossy().into_owned());
    if let Some(stem) = stem {
        element.set_attribute("name", stem);
    }
}

/// `a/./b/../c` → `a/c`, without touching the file system.
fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir
                if matches!(out.components().next_back(), Some(Component::Normal(_))) =>
            {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// Replaces each `<include file="…"/>` by the children of the included file's root.
pub(super) fn inline_includes(
    tree: &mut Element,
    dir: Option<&Path>,
) -> Result<(), (Option<Position>, String)> {
    inline(tree, dir, 0, 0)
}

/// Inlines the includes below `element`, which is `level` deep in its template, itself inside
/// `depth` includes.
fn inline(
    element: &mut Element,
    dir: Option<&Path>,
    depth: usize,
    level: usize,
) -> Result<(), (Option<Position>, String)> {
    let mut children = Vec::with_capacity(element.children.len());
    for mut child in std::mem::take(&mut element.children) {
        if level + 1 >= MAX_WORLD_DEPTH {
            return Err((
                Some(child.position),
                format!("elements nested deeper than {MAX_WORLD_DEPTH} (through includes)"),
            ));
        }
        if child.name != "include" {
            crate::stack::deep(|| inline(&mut child, dir, depth, level + 1))?;
            children.push(child);
            continue;
        }
        let position = Some(child.position);
        if depth >= MAX_INCLUDE_DEPTH {
            return Err((
                position,
                "includes nested too deeply (does a file include itself?)".into(),
            ));
        }
        let file = child
            .attribute("file")
            .ok_or((position, "<include> needs a `file`".to_owned()))?;
        let path = match dir {
            Some(dir) => dir.join(file),
            None => PathBuf::from(file),
        };
        let text =
            crate::bounded::read_text(&path, crate::bounded::TEMPLATE_LIMIT).map_err(|e| {
                (
                    position,
                    format!("cannot read included file {}: {e}", path.display()),
                )
            })?;
        let document = Element::parse(&text).map_err(|e| {
            (
                position,
                format!(
                    "in included file {} at {}: {}",
                    path.display(),
                    e.position,
                    e.message
                ),
            )
        })?;
        for stray in &document.stray_text {
            tracing::warn!("{}:{stray}", path.display());
        }
        let mut included = document.root;
        inline(&mut included, dir, depth + 1, level)?;
        children.extend(included.children);
    }
    element.children = children;
    Ok(())
}
