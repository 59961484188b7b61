//! Config values: what templates compute, tags assign, run configurations set and settings
//! structs are read from.
//!
//! A [`Value`] is an integer, a number, a boolean, a string, a list of values, or empty. A
//! [`Config`] maps names to values in the order they were set. [`Config::deserialize`] reads one
//! into any `serde` struct, so interfaces and plugins take typed settings.

mod de;
mod ser;
mod typed;

use std::collections::BTreeMap;
use std::fmt;

pub use de::SettingsError;
pub(crate) use typed::typed;

/// A config value.
///
/// # Examples
///
/// ```
/// use yarok_core::value::{IntoValue, Value};
///
/// let size = 0.05.into_value();
/// assert_eq!(size.as_f64(), Some(0.05));
/// assert_eq!([1, 2].into_value().to_string(), "1 2");
/// assert_eq!(Value::from_text("true").as_bool(), Some(true));
/// ```
#[derive(Clone, PartialEq)]
pub struct Value(pub(crate) evalexpr::Value);

impl Value {
    /// The empty value (`None` in templates).
    pub const EMPTY: Value = Value(evalexpr::Value::Empty);

    /// The number, for integers and numbers.
    pub fn as_f64(&self) -> Option<f64> {
        match self.0 {
            evalexpr::Value::Float(x) => Some(x),
            evalexpr::Value::Int(n) => Some(n as f64),
            _ => None,
        }
    }

    /// The integer.
    pub fn as_i64(&self) -> Option<i64> {
        match self.0 {
            evalexpr::Value::Int(n) => Some(n),
            _ => None,
        }
    }

    /// The boolean.
    pub fn as_bool(&self) -> Option<bool> {
        match self.0 {
            evalexpr::Value::Boolean(b) => Some(b),
            _ => None,
        }
    }

    /// The string.
    pub fn as_str(&self) -> Option<&str> {
        match &self.0 {
            evalexpr::Value::String(s) => Some(s),
            _ => None,
        }
    }

    /// The items, for lists.
    pub fn to_list(&self) -> Option<Vec<Value>> {
        match &self.0 {
            evalexpr::Value::Tuple(items) => Some(items.iter().cloned().map(Value).collect()),
            _ => None,
        }
    }

    /// Whether this is the empty value.
    pub fn is_empty(&self) -> bool {
        matches!(self.0, evalexpr::Value::Empty)
    }

    /// A value written on a command line or in a tag: TOML when it parses as a TOML value
    /// (`0.5`, `true`, `[1, 2]`, `"text"`), else the text itself as a string.
    pub fn from_text(text: &str) -> Value {
        format!("v = {text}")
            .parse::<toml::Table>()
            .ok()
            .and_then(|mut t| t.remove("v"))
            .and_then(Value::from_toml)
            .unwrap_or_else(|| text.into_value())
    }

    /// A TOML value; `None` for tables and dates.
    pub(crate) fn from_toml(value: toml::Value) -> Option<Value> {
        Some(Value(match value {
            toml::Value::String(s) => evalexpr::Value::String(s),
            toml::Value::Integer(n) => evalexpr::Value::Int(n),
            toml::Value::Float(x) => evalexpr::Value::Float(x),
            toml::Value::Boolean(b) => evalexpr::Value::Boolean(b),
            toml::Value::Array(items) => evalexpr::Value::Tuple(
                items
                    .into_iter()
                    .map(|item| Value::from_toml(item).map(|v| v.0))
                    .collect::<Option<_>>()?,
            ),
            toml::Value::Table(_) | toml::Value::Datetime(_) => return None,
        }))
    }

    /// Reads the value as `T`, converting as [`Config::deserialize`] does.
    ///
    /// # Errors
    ///
    /// [`SettingsError`] when the value does not fit `T`.
    pub fn deserialize<T: serde::de::DeserializeOwned>(&self) -> Result<T, SettingsError> {
        de::from_value(self)
    }

    /// What kind of value this is, for messages: "an integer", "a number", …
    pub fn kind(&self) -> &'static str {
        match self.0 {
            evalexpr::Value::Int(_) => "an integer",
            evalexpr::Value::Float(_) => "a number",
            evalexpr::Value::Boolean(_) => "true or false",
            evalexpr::Value::Tuple(_) => "a list",
            evalexpr::Value::Empty => "nothing",
            _ => "a string",
        }
    }
}

/// As templates print it: integers as integers, numbers in their shortest exact form, booleans
/// as `true`/`false`, lists as space-separated items.
impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&format_value(&self.0))
    }
}

impl fmt::Debug for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            evalexpr::Value::String(s) => write!(f, "{s:?}"),
            evalexpr::Value::Tuple(items) => f
                .debug_list()
                .entries(items.iter().cloned().map(Value))
                .finish(),
            evalexpr::Value::Empty => f.write_str("None"),
            _ => write!(f, "{self}"),
        }
    }
}

/// Config values: name → value, in the order they were set.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Config {
    entries: Vec<(String, Value)>,
}

impl Config {
    /// The value of `key`.
    pub fn get(&self, key: &str) -> Option<&Value> {
        self.entries.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }

    /// Sets `key`, keeping its place when it exists.
    pub fn set(&mut self, key: &str, value: Value) {
        match self.entries.iter_mut().find(|(k, _)| k == key) {
            Some(entry) => entry.1 = value,
            None => self.entries.push((key.to_owned(), value)),
        }
    }

    /// Every `(key, value)` in order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &Value)> {
        self.entries.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// Every key.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|(k, _)| k.as_str())
    }

    /// Whether no key is set.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Sets every key `other` sets, its values winning.
    pub fn merge(&mut self, other: &Config) {
        for (key, value) in other.iter() {
            self.set(key, value.clone());
        }
    }

    /// Reads the values into a settings struct: a key the struct has no field for, or a value
    /// of the wrong type, is an error naming the key (and, for a typo, the nearest field). Text
    /// given for a number or a boolean (`--set key=0.5` read as a string) is parsed.
    ///
    /// # Errors
    ///
    /// [`SettingsError`] naming the key; the caller adds where the value was set.
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_core::value::Config;
    ///
    /// #[derive(serde::Deserialize, Debug, PartialEq)]
    /// #[serde(default)]
    /// struct Serial { port: String, baud: u32 }
    /// impl Default for Serial {
    ///     fn default() -> Self { Serial { port: "/dev/ttyUSB0".into(), baud: 115_200 } }
    /// }
    ///
    /// let settings: Serial = Config::from([("baud", 250_000)]).deserialize()?;
    /// assert_eq!(settings, Serial { port: "/dev/ttyUSB0".into(), baud: 250_000 });
    ///
    /// let typo = Config::from([("bauds", 9600)]).deserialize::<Serial>().unwrap_err();
    /// assert_eq!(typo.to_string(), "no setting `bauds` (it has port, baud); did you mean `baud`?");
    /// # Ok::<(), yarok_core::value::SettingsError>(())
    /// ```
    pub fn deserialize<T: serde::de::DeserializeOwned>(&self) -> Result<T, SettingsError> {
        de::from_config(self, de::OtherKeys::Refused)
    }

    /// Reads the values the struct has fields for, leaving the others (a base component's
    /// config, values only its template uses) alone; a value of the wrong type is an error
    /// naming the key, as with [`Config::deserialize`].
    ///
    /// # Errors
    ///
    /// [`SettingsError`] naming the key.
    pub fn deserialize_fields<T: serde::de::DeserializeOwned>(&self) -> Result<T, SettingsError> {
        de::from_config(self, de::OtherKeys::Left)
    }

    /// The fields of a serde struct as config values, in the order it declares them: numbers,
    /// booleans, text, unit enum variants (as their names) and lists of them.
    ///
    /// # Errors
    ///
    /// [`SettingsError`] when `fields` is not a struct or a field holds something else (a map,
    /// a struct).
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_core::value::Config;
    ///
    /// #[derive(serde::Serialize)]
    /// struct Lamp { brightness: f64, rgb: [u8; 3], label: &'static str }
    ///
    /// let config = Config::from_fields(&Lamp { brightness: 0.5, rgb: [255, 200, 0], label: "desk" })?;
    /// assert_eq!(config.keys().collect::<Vec<_>>(), ["brightness", "rgb", "label"]);
    /// assert_eq!(config.get("rgb").unwrap().to_string(), "255 200 0");
    /// # Ok::<(), yarok_core::value::SettingsError>(())
    /// ```
    pub fn from_fields<T: serde::Serialize>(fields: &T) -> Result<Config, SettingsError> {
        ser::to_config(fields)
    }
}

impl<K: Into<String>, V: IntoValue, const N: usize> From<[(K, V); N]> for Config {
    fn from(entries: [(K, V); N]) -> Self {
        let mut config = Config::default();
        for (key, value) in entries {
            config.set(&key.into(), value.into_value());
        }
        config
    }
}

/// Config overrides by component path, applied over defaults and tag attributes.
pub type Overrides = BTreeMap<String, Config>;

/// Rust values usable as config values: numbers, booleans, strings and lists of them.
pub trait IntoValue {
    /// The config value.
    fn into_value(self) -> Value;
}

impl IntoValue for Value {
    fn into_value(self) -> Value {
        self
    }
}

macro_rules! into_value {
    ($($rust:ty => $variant:ident as $as:ty),* $(,)?) => {$(
        impl IntoValue for $rust {
            fn into_value(self) -> Value {
                Value(evalexpr::Value::$variant(self as $as))
            }
        }
    )*};
}

into_value!(i32 => Int as i64, i64 => Int as i64, u32 => Int as i64, f32 => Float as f64, f64 => Float as f64);

impl IntoValue for bool {
    fn into_value(self) -> Value {
        Value(evalexpr::Value::Boolean(self))
    }
}

impl IntoValue for &str {
    fn into_value(self) -> Value {
        Value(evalexpr::Value::String(self.to_owned()))
    }
}

impl IntoValue for String {
    fn into_value(self) -> Value {
        Value(evalexpr::Value::String(self))
    }
}

impl<T: IntoValue> IntoValue for Vec<T> {
    fn into_value(self) -> Value {
        Value(evalexpr::Value::Tuple(
            self.into_iter().map(|item| item.into_value().0).collect(),
        ))
    }
}

impl<T: IntoValue, const N: usize> IntoValue for [T; N] {
    fn into_value(self) -> Value {
        Vec::from(self).into_value()
    }
}

/// Formats a value the way templates print it: integers as integers, floats with the shortest
/// representation that reads back to the same number, booleans as `true`/`false`, lists and
/// tuples as space-separated items.
pub(crate) fn format_value(value: &evalexpr::Value) -> String {
    let mut out = String::new();
    write_value(value, &mut out);
    out
}

fn write_value(value: &evalexpr::Value, out: &mut String) {
    match value {
        evalexpr::Value::String(s) => out.push_str(s),
        evalexpr::Value::Float(x) => out.push_str(&format!("{x}")),
        evalexpr::Value::Int(n) => out.push_str(&n.to_string()),
        evalexpr::Value::Boolean(b) => out.push_str(if *b { "true" } else { "false" }),
        evalexpr::Value::Tuple(items) => {
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push(' ');
                }
                write_value(item, out);
            }
        }
        evalexpr::Value::Empty => {}
    }
}
