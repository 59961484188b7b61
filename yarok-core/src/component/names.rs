//! Names a component's template defines, by kind and local name.

use std::collections::BTreeMap;
use std::fmt;

/// Kinds of named objects a component can look up by local name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[non_exhaustive]
pub enum NameKind {
    /// `<body>`.
    Body,
    /// `<joint>`, `<freejoint>`.
    Joint,
    /// `<geom>`.
    Geom,
    /// `<site>`.
    Site,
    /// `<camera>`.
    Camera,
    /// `<light>`.
    Light,
    /// Any element under `<actuator>`.
    Actuator,
    /// Any element under `<sensor>`.
    Sensor,
    /// `<spatial>`, `<fixed>` tendons.
    Tendon,
    /// `<mesh>`.
    Mesh,
    /// `<material>`.
    Material,
    /// `<texture>`.
    Texture,
    /// `<hfield>`.
    Hfield,
    /// Any element under `<equality>`.
    Equality,
    /// `<key>`.
    Keyframe,
    /// `<default class="..">`.
    Class,
    /// Anything else with a name (`<numeric>`, `<pair>`, `<skin>`, …).
    Other,
}

impl fmt::Display for NameKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&format!("{self:?}").to_lowercase())
    }
}

impl NameKind {
    pub(crate) fn of(tag: &str, section: &str) -> Self {
        match (section, tag) {
            ("actuator", _) => Self::Actuator,
            ("sensor", _) => Self::Sensor,
            ("equality", _) => Self::Equality,
            (_, "body") => Self::Body,
            (_, "joint" | "freejoint") => Self::Joint,
            (_, "geom") => Self::Geom,
            (_, "site") => Self::Site,
            (_, "camera") => Self::Camera,
            (_, "light") => Self::Light,
            (_, "spatial" | "fixed") => Self::Tendon,
            (_, "mesh") => Self::Mesh,
            (_, "material") => Self::Material,
            (_, "texture") => Self::Texture,
            (_, "hfield") => Self::Hfield,
            (_, "key") => Self::Keyframe,
            (_, "default") => Self::Class,
            _ => Self::Other,
        }
    }
}

/// The names one component defined, local name → name in the composed model.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct NameMap {
    names: BTreeMap<(NameKind, String), String>,
}

impl NameMap {
    /// The composed-model name of the object this component calls `local`.
    pub fn get(&self, kind: NameKind, local: &str) -> Option<&str> {
        self.names
            .get(&(kind, local.to_owned()))
            .map(String::as_str)
    }

    /// Every `(kind, local, composed)` name, sorted by kind then local name.
    pub fn iter(&self) -> impl Iterator<Item = (NameKind, &str, &str)> {
        self.names
            .iter()
            .map(|((kind, local), global)| (*kind, local.as_str(), global.as_str()))
    }

    pub(crate) fn insert(&mut self, kind: NameKind, local: &str, global: &str) {
        self.names
            .insert((kind, local.to_owned()), global.to_owned());
    }

    /// How many names the component defined.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether the component defined no names.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }
}
