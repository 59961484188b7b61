//! A `serde` struct's fields as a [`Config`]: how a component declares its config's defaults.

use serde::Serialize;
use serde::ser::{self, Impossible, SerializeStruct};

use evalexpr::Value as Inner;

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
        let value = value.serialize(Item).map_err(|e| SettingsError {
            key: Some(key.to_owned()),
            message: format!("`{key}` {}", e.message),
        })?;
        self.0.set(key, Value(value));
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

/// One field's value: a number, a boolean, text, a unit variant's name, nothing, or a list.
struct Item;

/// A list's items as they are serialized.
#[derive(Default)]
struct Items(Vec<Inner>);

fn not_an_item<T>(what: &str) -> Result<T, SettingsError> {
    Err(ser::Error::custom(format!(
        "is {what}, which config values cannot hold"
    )))
}

macro_rules! items {
    ($($method:ident($rust:ty) => $variant:ident as $as:ty;)*) => {$(
        fn $method(self, value: $rust) -> Result<Inner, SettingsError> {
            Ok(Inner::$variant(value as $as))
        }
    )*};
}

impl ser::Serializer for Item {
    type Ok = Inner;
    type Error = SettingsError;
    type SerializeSeq = Items;
    type SerializeTuple = Items;
    type SerializeTupleStruct = Items;
    type SerializeTupleVariant = Impossible<Inner, SettingsError>;
    type SerializeMap = Impossible<Inner, SettingsError>;
    type SerializeStruct = Impossible<Inner, SettingsError>;
    type SerializeStructVariant = Impossible<Inner, SettingsError>;

    items! {
        serialize_i8(i8) => Int as i64;
        serialize_i16(i16) => Int as i64;
        serialize_i32(i32) => Int as i64;
        serialize_i64(i64) => Int as i64;
        serialize_u8(u8) => Int as i64;
        serialize_u16(u16) => Int as i64;
        serialize_u32(u32) => Int as i64;
        serialize_f32(f32) => Float as f64;
        serialize_f64(f64) => Float as f64;
    }

    fn serialize_u64(self, value: u64) -> Result<Inner, SettingsError> {
        i64::try_from(value)
            .map(Inner::Int)
            .or_else(|_| not_an_item("an integer beyond 2⁶³"))
    }

    fn serialize_bool(self, value: bool) -> Result<Inner, SettingsError> {
        Ok(Inner::Boolean(value))
    }

    fn serialize_char(self, value: char) -> Result<Inner, SettingsError> {
        Ok(Inner::String(value.to_string()))
    }

    fn serialize_str(self, value: &str) -> Result<Inner, SettingsError> {
        Ok(Inner::String(value.to_owned()))
    }

    fn serialize_bytes(self, _: &[u8]) -> Result<Inner, SettingsError> {
        not_an_item("bytes")
    }

    fn serialize_none(self) -> Result<Inner, SettingsError> {
        Ok(Inner::Empty)
    }

    fn serialize_some<T: ?Sized + Serialize>(self, value: &T) -> Result<Inner, SettingsError> {
        value.serialize(self)
    }

    fn serialize_unit(self) -> Result<Inner, SettingsError> {
        Ok(Inner::Empty)
    }

    fn serialize_unit_struct(self, _: &'static str) -> Result<Inner, SettingsError> {
        Ok(Inner::Empty)
    }

    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<Inner, SettingsError> {
        Ok(Inner::String(variant.to_owned()))
    }

    fn serialize_newtype_struct<T: ?Sized + Serialize>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<Inner, SettingsError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: ?Sized + Serialize>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<Inner, SettingsError> {
        not_an_item("an enum variant with data")
    }

    fn serialize_seq(self, length: Option<usize>) -> Result<Items, SettingsError> {
        Ok(Items(Vec::with_capacity(length.unwrap_or(0))))
    }

    fn serialize_tuple(self, length: usize) -> Result<Items, SettingsError> {
        self.serialize_seq(Some(length))
    }

    fn serialize_tuple_struct(
        self,
        _: &'static str,
        length: usize,
    ) -> Result<Items, SettingsError> {
        self.serialize_seq(Some(length))
    }

    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, SettingsError> {
        not_an_item("an enum variant with data")
    }

    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, SettingsError> {
        not_an_item("a table")
    }

    fn serialize_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStruct, SettingsError> {
        not_an_item("a table")
    }

    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, SettingsError> {
        not_an_item("an enum variant with data")
    }
}

impl Items {
    fn push<T: ?Sized + Serialize>(&mut self, item: &T) -> Result<(), SettingsError> {
        self.0.push(item.serialize(Item)?);
        Ok(())
    }
}

impl ser::SerializeSeq for Items {
    type Ok = Inner;
    type Error = SettingsError;

    fn serialize_element<T: ?Sized + Serialize>(&mut self, item: &T) -> Result<(), SettingsError> {
        self.push(item)
    }

    fn end(self) -> Result<Inner, SettingsError> {
        Ok(Inner::Tuple(self.0))
    }
}

impl ser::SerializeTuple for Items {
    type Ok = Inner;
    type Error = SettingsError;

    fn serialize_element<T: ?Sized + Serialize>(&mut self, item: &T) -> Result<(), SettingsError> {
        self.push(item)
    }

    fn end(self) -> Result<Inner, SettingsError> {
        Ok(Inner::Tuple(self.0))
    }
}

impl ser::SerializeTupleStruct for Items {
    type Ok = Inner;
    type Error = SettingsError;

    fn serialize_field<T: ?Sized + Serialize>(&mut self, item: &T) -> Result<(), SettingsError> {
        self.push(item)
    }

    fn end(self) -> Result<Inner, SettingsError> {
        Ok(Inner::Tuple(self.0))
    }
}
