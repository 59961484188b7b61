//! Reading a [`Config`] into a `serde` settings struct.

use serde::de::{self, DeserializeOwned, IntoDeserializer, Visitor};

use super::{Config, Value};
use crate::suggest::did_you_mean;

/// A setting that a settings struct cannot take.
#[derive(Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct SettingsError {
    /// The key at fault, when one is.
    pub key: Option<String>,
    /// What is wrong, naming the key.
    pub message: String,
}

crate::debug_as_report!(SettingsError);

impl de::Error for SettingsError {
    fn custom<T: std::fmt::Display>(message: T) -> Self {
        SettingsError {
            key: None,
            message: message.to_string(),
        }
    }

    fn unknown_variant(variant: &str, expected: &'static [&'static str]) -> Self {
        de::Error::custom(format!(
            "unknown value `{variant}` (expected one of {}){}",
            expected.join(", "),
            did_you_mean(variant, expected.iter().copied())
        ))
    }
}

impl SettingsError {
    /// The error, as the value of `key`'s.
    pub(crate) fn at(self, key: &str) -> Self {
        SettingsError {
            message: format!("`{key}` {}", self.message),
            key: Some(key.to_owned()),
        }
    }
}

/// What reading a config into a struct does with a key the struct has no field for.
#[derive(Clone, Copy)]
pub(super) enum OtherKeys {
    /// An error naming the key and the nearest field.
    Refused,
    /// Left alone.
    Left,
}

pub(super) fn from_config<T: DeserializeOwned>(
    config: &Config,
    other_keys: OtherKeys,
) -> Result<T, SettingsError> {
    T::deserialize(ConfigDeserializer {
        config,
        other_keys,
        fields: None,
    })
}

struct ConfigDeserializer<'a> {
    config: &'a Config,
    other_keys: OtherKeys,
    fields: Option<&'static [&'static str]>,
}

impl<'de> de::Deserializer<'de> for ConfigDeserializer<'_> {
    type Error = SettingsError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        let fields = self.fields;
        visitor.visit_map(Entries {
            entries: self
                .config
                .iter()
                .filter(move |(key, _)| fields.is_none_or(|fields| fields.contains(key))),
            value: None,
        })
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, SettingsError> {
        if let OtherKeys::Left = self.other_keys {
            return Self {
                fields: Some(fields),
                ..self
            }
            .deserialize_any(visitor);
        }
        if let Some(key) = self.config.keys().find(|key| !fields.contains(key)) {
            let known = if fields.is_empty() {
                "it takes none".to_owned()
            } else {
                format!("it has {}", fields.join(", "))
            };
            return Err(SettingsError {
                key: Some(key.to_owned()),
                message: format!(
                    "no setting `{key}` ({known}){}",
                    did_you_mean(key, fields.iter().copied())
                ),
            });
        }
        self.deserialize_any(visitor)
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
        ignored_any
    }
}

struct Entries<'a, I> {
    entries: I,
    value: Option<(&'a str, &'a Value)>,
}

impl<'de, 'a, I: Iterator<Item = (&'a str, &'a Value)>> de::MapAccess<'de> for Entries<'a, I> {
    type Error = SettingsError;

    fn next_key_seed<K: de::DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, SettingsError> {
        let Some((key, value)) = self.entries.next() else {
            return Ok(None);
        };
        self.value = Some((key, value));
        seed.deserialize(key.into_deserializer()).map(Some)
    }

    fn next_value_seed<S: de::DeserializeSeed<'de>>(
        &mut self,
        seed: S,
    ) -> Result<S::Value, SettingsError> {
        let (key, value) = self
            .value
            .take()
            .ok_or_else(|| de::Error::custom("a value without its key"))?;
        seed.deserialize(ValueDeserializer(value))
            .map_err(|error| error.at(key))
    }
}

struct ValueDeserializer<'a>(&'a Value);

impl ValueDeserializer<'_> {
    fn mismatch(&self, expected: &str) -> SettingsError {
        de::Error::custom(format!("expects {expected}, got {:?}", self.0))
    }

    /// The number the value holds or, for text, spells.
    fn number<T: std::str::FromStr>(&self, expected: &str) -> Result<T, SettingsError> {
        let text = match self.0.as_str() {
            Some(text) => text.trim().to_owned(),
            None => self.0.to_string(),
        };
        let numeric = self.0.as_str().is_some() || self.0.as_f64().is_some();
        numeric
            .then(|| text.parse().ok())
            .flatten()
            .ok_or_else(|| self.mismatch(expected))
    }
}

macro_rules! integers {
    ($($method:ident: $rust:ty => $visit:ident, $expected:literal;)*) => {$(
        fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
            if self.0.as_f64().is_some() && self.0.as_i64().is_none() {
                return Err(self.mismatch($expected));
            }
            visitor.$visit(self.number::<$rust>($expected)?)
        }
    )*};
}

impl<'de> de::Deserializer<'de> for ValueDeserializer<'_> {
    type Error = SettingsError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        match &self.0.0 {
            evalexpr::Value::Int(n) => visitor.visit_i64(*n),
            evalexpr::Value::Float(x) => visitor.visit_f64(*x),
            evalexpr::Value::Boolean(b) => visitor.visit_bool(*b),
            evalexpr::Value::String(s) => visitor.visit_str(s),
            evalexpr::Value::Empty => visitor.visit_unit(),
            evalexpr::Value::Tuple(_) => self.deserialize_seq(visitor),
        }
    }

    fn deserialize_bool<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        match (self.0.as_bool(), self.0.as_str().map(str::trim)) {
            (Some(b), _) => visitor.visit_bool(b),
            (_, Some("true" | "True")) => visitor.visit_bool(true),
            (_, Some("false" | "False")) => visitor.visit_bool(false),
            _ => Err(self.mismatch("true or false")),
        }
    }

    integers! {
        deserialize_i8: i8 => visit_i8, "an integer";
        deserialize_i16: i16 => visit_i16, "an integer";
        deserialize_i32: i32 => visit_i32, "an integer";
        deserialize_i64: i64 => visit_i64, "an integer";
        deserialize_u8: u8 => visit_u8, "an integer from 0";
        deserialize_u16: u16 => visit_u16, "an integer from 0";
        deserialize_u32: u32 => visit_u32, "an integer from 0";
        deserialize_u64: u64 => visit_u64, "an integer from 0";
    }

    fn deserialize_f32<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        visitor.visit_f32(self.number("a number")?)
    }

    fn deserialize_f64<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        visitor.visit_f64(self.number("a number")?)
    }

    fn deserialize_str<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        match self.0.as_str() {
            Some(text) => visitor.visit_str(text),
            None if self.0.as_f64().is_some() => visitor.visit_string(self.0.to_string()),
            None => Err(self.mismatch("text")),
        }
    }

    fn deserialize_string<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        self.deserialize_str(visitor)
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        if self.0.is_empty() {
            visitor.visit_none()
        } else {
            visitor.visit_some(self)
        }
    }

    fn deserialize_seq<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, SettingsError> {
        let items = self.0.to_list().ok_or_else(|| self.mismatch("a list"))?;
        let mut index = 0;
        let mut error_at = None;
        let result = visitor.visit_seq(Items {
            items: items.iter(),
            index: &mut index,
        });
        if result.is_err() {
            error_at = Some(index.saturating_sub(1));
        }
        result.map_err(|e| SettingsError {
            message: match error_at {
                Some(at) => format!("(item {at}) {}", e.message),
                None => e.message,
            },
            key: e.key,
        })
    }

    fn deserialize_tuple<V: Visitor<'de>>(
        self,
        _len: usize,
        visitor: V,
    ) -> Result<V::Value, SettingsError> {
        self.deserialize_seq(visitor)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, SettingsError> {
        let text = self.0.as_str().ok_or_else(|| self.mismatch("a name"))?;
        visitor.visit_enum(text.into_deserializer())
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, SettingsError> {
        visitor.visit_newtype_struct(self)
    }

    serde::forward_to_deserialize_any! {
        i128 u128 char bytes byte_buf unit unit_struct tuple_struct map struct identifier
        ignored_any
    }
}

struct Items<'i, I> {
    items: I,
    index: &'i mut usize,
}

impl<'de, 'a, I: Iterator<Item = &'a Value>> de::SeqAccess<'de> for Items<'_, I> {
    type Error = SettingsError;

    fn next_element_seed<S: de::DeserializeSeed<'de>>(
        &mut self,
        seed: S,
    ) -> Result<Option<S::Value>, SettingsError> {
        let Some(item) = self.items.next() else {
            return Ok(None);
        };
        *self.index += 1;
        seed.deserialize(ValueDeserializer(item)).map(Some)
    }
}

pub(super) fn from_value<T: DeserializeOwned>(value: &Value) -> Result<T, SettingsError> {
    T::deserialize(ValueDeserializer(value))
}
