//! RTDE variable types and values, and recipes: the named, typed variables a data package
//! carries, in order, big-endian.

/// The type of an RTDE variable, as the controller names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RtdeType {
    /// `BOOL`: one byte, 0 or 1.
    Bool,
    /// `UINT8`.
    Uint8,
    /// `UINT32`.
    Uint32,
    /// `UINT64`.
    Uint64,
    /// `INT32`.
    Int32,
    /// `DOUBLE`.
    Double,
    /// `VECTOR3D`: three doubles.
    Vector3d,
    /// `VECTOR6D`: six doubles (joints, or a pose `x, y, z, rx, ry, rz`).
    Vector6d,
    /// `VECTOR6INT32`.
    Vector6Int32,
    /// `VECTOR6UINT32`.
    Vector6Uint32,
}

impl RtdeType {
    /// Every type, in the order of the RTDE guide's table.
    pub const ALL: [RtdeType; 10] = [
        RtdeType::Bool,
        RtdeType::Uint8,
        RtdeType::Uint32,
        RtdeType::Uint64,
        RtdeType::Int32,
        RtdeType::Double,
        RtdeType::Vector3d,
        RtdeType::Vector6d,
        RtdeType::Vector6Int32,
        RtdeType::Vector6Uint32,
    ];

    /// The controller's name for the type (`VECTOR6D`).
    pub fn name(self) -> &'static str {
        match self {
            RtdeType::Bool => "BOOL",
            RtdeType::Uint8 => "UINT8",
            RtdeType::Uint32 => "UINT32",
            RtdeType::Uint64 => "UINT64",
            RtdeType::Int32 => "INT32",
            RtdeType::Double => "DOUBLE",
            RtdeType::Vector3d => "VECTOR3D",
            RtdeType::Vector6d => "VECTOR6D",
            RtdeType::Vector6Int32 => "VECTOR6INT32",
            RtdeType::Vector6Uint32 => "VECTOR6UINT32",
        }
    }

    /// The type the controller calls `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }

    /// Bytes a value of the type takes in a data package.
    pub fn size(self) -> usize {
        match self {
            RtdeType::Bool | RtdeType::Uint8 => 1,
            RtdeType::Uint32 | RtdeType::Int32 => 4,
            RtdeType::Uint64 | RtdeType::Double => 8,
            RtdeType::Vector3d => 24,
            RtdeType::Vector6d => 48,
            RtdeType::Vector6Int32 | RtdeType::Vector6Uint32 => 24,
        }
    }
}

/// A value of an RTDE variable.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Value {
    /// `BOOL`.
    Bool(bool),
    /// `UINT8`.
    Uint8(u8),
    /// `UINT32`.
    Uint32(u32),
    /// `UINT64`.
    Uint64(u64),
    /// `INT32`.
    Int32(i32),
    /// `DOUBLE`.
    Double(f64),
    /// `VECTOR3D`.
    Vector3d([f64; 3]),
    /// `VECTOR6D`.
    Vector6d([f64; 6]),
    /// `VECTOR6INT32`.
    Vector6Int32([i32; 6]),
    /// `VECTOR6UINT32`.
    Vector6Uint32([u32; 6]),
}

impl Value {
    /// The value's type.
    pub fn rtde_type(&self) -> RtdeType {
        match self {
            Value::Bool(_) => RtdeType::Bool,
            Value::Uint8(_) => RtdeType::Uint8,
            Value::Uint32(_) => RtdeType::Uint32,
            Value::Uint64(_) => RtdeType::Uint64,
            Value::Int32(_) => RtdeType::Int32,
            Value::Double(_) => RtdeType::Double,
            Value::Vector3d(_) => RtdeType::Vector3d,
            Value::Vector6d(_) => RtdeType::Vector6d,
            Value::Vector6Int32(_) => RtdeType::Vector6Int32,
            Value::Vector6Uint32(_) => RtdeType::Vector6Uint32,
        }
    }

    /// The value as the controller sends it: big-endian.
    pub fn encode(&self, out: &mut Vec<u8>) {
        match *self {
            Value::Bool(v) => out.push(u8::from(v)),
            Value::Uint8(v) => out.push(v),
            Value::Uint32(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Uint64(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Int32(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Double(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Vector3d(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
            Value::Vector6d(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
            Value::Vector6Int32(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
            Value::Vector6Uint32(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
        }
    }

    /// A value of `rtde_type` from the front of `bytes`, which must hold at least its size.
    fn decode(rtde_type: RtdeType, bytes: &[u8]) -> Self {
        let word = |at: usize| -> [u8; 4] { bytes[at..at + 4].try_into().expect("4 bytes") };
        let double = |at: usize| -> f64 {
            f64::from_be_bytes(bytes[at..at + 8].try_into().expect("8 bytes"))
        };
        match rtde_type {
            RtdeType::Bool => Value::Bool(bytes[0] != 0),
            RtdeType::Uint8 => Value::Uint8(bytes[0]),
            RtdeType::Uint32 => Value::Uint32(u32::from_be_bytes(word(0))),
            RtdeType::Int32 => Value::Int32(i32::from_be_bytes(word(0))),
            RtdeType::Uint64 => {
                Value::Uint64(u64::from_be_bytes(bytes[..8].try_into().expect("8 bytes")))
            }
            RtdeType::Double => Value::Double(double(0)),
            RtdeType::Vector3d => Value::Vector3d(std::array::from_fn(|i| double(8 * i))),
            RtdeType::Vector6d => Value::Vector6d(std::array::from_fn(|i| double(8 * i))),
            RtdeType::Vector6Int32 => {
                Value::Vector6Int32(std::array::from_fn(|i| i32::from_be_bytes(word(4 * i))))
            }
            RtdeType::Vector6Uint32 => {
                Value::Vector6Uint32(std::array::from_fn(|i| u32::from_be_bytes(word(4 * i))))
            }
        }
    }
}

/// A recipe: the variables a data package carries, in order, with their types, under the id
/// the controller gave it.
#[derive(Debug, Clone, PartialEq)]
pub struct Recipe {
    /// The controller's id for the recipe (the first byte of its data packages).
    pub id: u8,
    /// The variables' names and types, in package order.
    pub variables: Vec<(String, RtdeType)>,
}

/// A data package does not match its recipe.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum RecipeError {
    /// The package is not as long as the recipe's variables.
    #[error("recipe {recipe}: {got} bytes of values, not {expected}")]
    Length {
        /// The recipe.
        recipe: u8,
        /// Bytes the recipe's values take.
        expected: usize,
        /// Bytes the package holds.
        got: usize,
    },
    /// A value is not of its variable's type.
    #[error("recipe {recipe}: `{variable}` is {expected}, not {got}")]
    Type {
        /// The recipe.
        recipe: u8,
        /// The variable.
        variable: String,
        /// Its type's name.
        expected: &'static str,
        /// The value's type's name.
        got: &'static str,
    },
    /// Fewer or more values than the recipe has variables.
    #[error("recipe {recipe}: {got} values for {expected} variables")]
    Count {
        /// The recipe.
        recipe: u8,
        /// Its variables.
        expected: usize,
        /// The values given.
        got: usize,
    },
}

impl Recipe {
    /// Bytes its values take in a data package.
    pub fn size(&self) -> usize {
        self.variables.iter().map(|(_, t)| t.size()).sum()
    }

    /// The values of a data package's payload (after the recipe id).
    ///
    /// # Errors
    ///
    /// [`RecipeError::Length`] when the payload is not exactly the recipe's size.
    pub fn decode(&self, payload: &[u8]) -> Result<Vec<Value>, RecipeError> {
        if payload.len() != self.size() {
            return Err(RecipeError::Length {
                recipe: self.id,
                expected: self.size(),
                got: payload.len(),
            });
        }
        let mut at = 0;
        let values = self.variables.iter().map(|(_, rtde_type)| {
            let value = Value::decode(*rtde_type, &payload[at..]);
            at += rtde_type.size();
            value
        });
        Ok(values.collect())
    }

    /// A data package's payload (after the recipe id) for `values`, one a variable.
    ///
    /// # Errors
    ///
    /// [`RecipeError`] when the values do not match the variables in number or type.
    pub fn encode(&self, values: &[Value]) -> Result<Vec<u8>, RecipeError> {
        if values.len() != self.variables.len() {
            return Err(RecipeError::Count {
                recipe: self.id,
                expected: self.variables.len(),
                got: values.len(),
            });
        }
        let mut out = Vec::with_capacity(self.size());
        for ((name, rtde_type), value) in self.variables.iter().zip(values) {
            if value.rtde_type() != *rtde_type {
                return Err(RecipeError::Type {
                    recipe: self.id,
                    variable: name.clone(),
                    expected: rtde_type.name(),
                    got: value.rtde_type().name(),
                });
            }
            value.encode(&mut out);
        }
        Ok(out)
    }
}
