//! Config values converted to the type of their key's default (`"0.5"` → `0.5` for a float key).

use evalexpr::Value as Inner;

use super::{Config, Value};
use crate::suggest::did_you_mean;

/// A config value converted to the type of the key's default.
pub(crate) fn typed(defaults: &Config, key: &str, value: Value) -> Result<Value, String> {
    let Some(default) = defaults.get(key) else {
        let keys: Vec<&str> = defaults.keys().collect();
        let known = if keys.is_empty() {
            "it has none".to_owned()
        } else {
            format!("it has {}", keys.join(", "))
        };
        let placing = if ["pos", "quat", "euler", "axisangle", "xyaxes", "zaxis"].contains(&key) {
            "; a component is placed by a `<body>` around its tag, by `parent=` (a body or site), \
             or by a config key of its own that its template uses"
        } else {
            ""
        };
        return Err(format!(
            "no config key `{key}` ({known}){}{placing}",
            did_you_mean(key, keys.iter().copied())
        ));
    };
    let mismatch = |value: &Value| {
        let expects = match default.0 {
            Inner::Tuple(_) => "a list of numbers",
            _ => default.kind(),
        };
        format!("`{key}` expects {expects}, got {:?}", value.to_string())
    };
    let converted = match (&default.0, value.0) {
        (Inner::Float(_), Inner::Int(n)) => Inner::Float(n as f64),
        (Inner::Int(_), Inner::Int(n)) => Inner::Int(n),
        (Inner::Float(_), Inner::Float(x)) => Inner::Float(x),
        (Inner::Boolean(_), Inner::Boolean(b)) => Inner::Boolean(b),
        (Inner::Tuple(_), Inner::Tuple(items)) => Inner::Tuple(items),
        (Inner::String(_) | Inner::Empty, value) => value,
        (_, Inner::String(text)) => {
            return parse_as(&default.0, &text)
                .map(Value)
                .ok_or_else(|| mismatch(&Value(Inner::String(text))));
        }
        (_, value) => return Err(mismatch(&Value(value))),
    };
    Ok(Value(converted))
}

fn parse_as(default: &Inner, text: &str) -> Option<Inner> {
    let text = text.trim();
    match default {
        Inner::Int(_) => text.parse().ok().map(Inner::Int),
        Inner::Float(_) => text.parse().ok().map(Inner::Float),
        Inner::Boolean(_) => match text {
            "true" | "True" => Some(Inner::Boolean(true)),
            "false" | "False" => Some(Inner::Boolean(false)),
            _ => None,
        },
        Inner::Tuple(_) => text
            .split_whitespace()
            .map(|item| {
                item.parse()
                    .ok()
                    .map(Inner::Int)
                    .or_else(|| item.parse().ok().map(Inner::Float))
            })
            .collect::<Option<Vec<_>>>()
            .map(Inner::Tuple),
        _ => Some(Inner::String(text.to_owned())),
    }
}
