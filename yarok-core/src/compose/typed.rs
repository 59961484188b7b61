//! Config values converted to the type of their key's default (`"0.5"` → `0.5` for a float key).

use evalexpr::Value;

use super::Config;
use crate::suggest::did_you_mean;
use crate::template::expr::format_value;

/// A config value converted to the type of the key's default.
pub(crate) fn typed(defaults: &Config, key: &str, value: Value) -> Result<Value, String> {
    let Some(default) = defaults.get(key) else {
        let keys: Vec<&str> = defaults.keys().collect();
        let known = if keys.is_empty() {
            "it has none".to_owned()
        } else {
            format!("it has {}", keys.join(", "))
        };
        return Err(format!(
            "no config key `{key}` ({known}){}",
            did_you_mean(key, keys.iter().copied())
        ));
    };
    let mismatch = |value: &Value| {
        format!(
            "`{key}` expects {}, got {:?}",
            kind(default),
            format_value(value)
        )
    };
    match (default, value) {
        (Value::Float(_), Value::Int(n)) => Ok(Value::Float(n as f64)),
        (Value::Int(_), Value::Int(n)) => Ok(Value::Int(n)),
        (Value::Float(_), Value::Float(x)) => Ok(Value::Float(x)),
        (Value::Boolean(_), Value::Boolean(b)) => Ok(Value::Boolean(b)),
        (Value::Tuple(_), Value::Tuple(items)) => Ok(Value::Tuple(items)),
        (Value::String(_) | Value::Empty, value) => Ok(value),
        (_, Value::String(text)) => {
            parse_as(default, &text).ok_or_else(|| mismatch(&Value::String(text)))
        }
        (_, value) => Err(mismatch(&value)),
    }
}

fn kind(value: &Value) -> &'static str {
    match value {
        Value::Int(_) => "an integer",
        Value::Float(_) => "a number",
        Value::Boolean(_) => "true or false",
        Value::Tuple(_) => "a list of numbers",
        _ => "a string",
    }
}

fn parse_as(default: &Value, text: &str) -> Option<Value> {
    let text = text.trim();
    match default {
        Value::Int(_) => text.parse().ok().map(Value::Int),
        Value::Float(_) => text.parse().ok().map(Value::Float),
        Value::Boolean(_) => match text {
            "true" | "True" => Some(Value::Boolean(true)),
            "false" | "False" => Some(Value::Boolean(false)),
            _ => None,
        },
        Value::Tuple(_) => text
            .split_whitespace()
            .map(|item| {
                item.parse()
                    .ok()
                    .map(Value::Int)
                    .or_else(|| item.parse().ok().map(Value::Float))
            })
            .collect::<Option<Vec<_>>>()
            .map(Value::Tuple),
        _ => Some(Value::String(text.to_owned())),
    }
}
