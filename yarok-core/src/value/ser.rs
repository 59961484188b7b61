//! A `serde` struct's fields as a [`Config`]: how a component declares its config's defaults.

use serde::Serialize;
use serde::ser::{self, Impossible, SerializeStruct};

use super::{Config, SettingsError, Value};

pub(super) fn to_config<T: Serialize>(fields: &T) -> Result<Config, SettingsError> {
    fields.serialize(Fields::default())
}

impl ser::Error for SettingsError {
    fn custom<T: std::fmt::Display>(message: T) -> Self {
        SettingsError {
            key: None,
            message: message.to_string(),
        }
    }
}

/// Collects a struct's fields; anything else at the top is refused.
#[derive(Default)]
struct Fields(Config);

fn not_a_struct<T>(what: &str) -> Result<T, SettingsError> {
    Err(ser::Error::custom(format!(
        "a config is a struct of named fields, not {what}"
    )))
}

impl SerializeStruct for Fields {
    type Ok = Config;
    type Error = SettingsError;

    fn serialize_field<T: ?Sized + Serialize>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), SettingsError> {
        let refused = |message: String| SettingsError {
            key: Some(key.to_owned()),
            message: format!("`{key}` {message}"),
        };
        let value = toml::Value::try_from(value).map_err(|e| refused(e.to_string()))?;
        let value = Value::from_toml(value).ok_or_else(|| {
            refused("is a table or a date, which config values cannot hold".into())
        })?;
        self.0.set(key, value);
        Ok(())
    }

    fn end(self) -> Result<Config, SettingsError> {
        Ok(self.0)
    }
}

macro_rules! refuse {
    ($($method:ident($($arg:ty),*) -> $ok:ty, $what:literal;)*) => {$(
        fn $method(self, $(_: $arg),*) -> Result<$ok, SettingsError> {
            not_a_struct($what)
        }
    )*};
}

impl ser::Serializer for Fields {
    type Ok = Config;
    type Error = SettingsError;
    type SerializeSeq = Impossible<Config, SettingsError>;
    type SerializeTuple = Impossible<Config, SettingsError>;
    type SerializeTupleStruct = Impossible<Config, SettingsError>;
    type SerializeTupleVariant = Impossible<Config, SettingsError>;
    type SerializeMap = Impossible<Config, SettingsError>;
    type SerializeStruct = Self;
    type SerializeStructVariant = Impossible<Config, SettingsError>;

    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self, SettingsError> {
        Ok(self)
    }

    refuse! {
        serialize_bool(bool) -> Config, "a boolean";
        serialize_i8(i8) -> Config, "a number";
        serialize_i16(i16) -> Config, "a number";
        serialize_i32(i32) -> Config, "a number";
        serialize_i64(i64) -> Config, "a number";
        serialize_u8(u8) -> Config, "a number";
        serialize_u16(u16) -> Config, "a number";
        serialize_u32(u32) -> Config, "a number";
        serialize_u64(u64) -> Config, "a number";
        serialize_f32(f32) -> Config, "a number";
        serialize_f64(f64) -> Config, "a number";
        serialize_char(char) -> Config, "a character";
        serialize_str(&str) -> Config, "text";
        serialize_bytes(&[u8]) -> Config, "bytes";
        serialize_none() -> Config, "an option";
        serialize_unit() -> Config, "a unit";
        serialize_unit_struct(&'static str) -> Config, "a unit struct";
        serialize_unit_variant(&'static str, u32, &'static str) -> Config, "an enum";
        serialize_seq(Option<usize>) -> Self::SerializeSeq, "a list";
        serialize_tuple(usize) -> Self::SerializeTuple, "a tuple";
        serialize_tuple_struct(&'static str, usize) -> Self::SerializeTupleStruct, "a tuple struct";
        serialize_tuple_variant(&'static str, u32, &'static str, usize) -> Self::SerializeTupleVariant, "an enum";
        serialize_map(Option<usize>) -> Self::SerializeMap, "a map";
        serialize_struct_variant(&'static str, u32, &'static str, usize) -> Self::SerializeStructVariant, "an enum";
    }

    fn serialize_some<T: ?Sized + Serialize>(self, _: &T) -> Result<Config, SettingsError> {
        not_a_struct("an option")
    }

    fn serialize_newtype_struct<T: ?Sized + Serialize>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<Config, SettingsError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: ?Sized + Serialize>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<Config, SettingsError> {
        not_a_struct("an enum")
    }
}
