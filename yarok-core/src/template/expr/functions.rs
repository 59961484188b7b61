//! Python's meaning for the operators and builtins expressions use, on evalexpr's values.

use evalexpr::{EvalexprError, EvalexprResult, Value};

/// The functions templates may call, besides operators. `math.` ones also have constants
/// `math.pi`, `math.e`, `math.tau`.
pub const FUNCTIONS: [&str; 25] = [
    "abs",
    "bool",
    "float",
    "int",
    "len",
    "list",
    "max",
    "min",
    "range",
    "round",
    "str",
    "sum",
    "tuple",
    "math.sqrt",
    "math.sin",
    "math.cos",
    "math.tan",
    "math.asin",
    "math.acos",
    "math.atan",
    "math.atan2",
    "math.radians",
    "math.degrees",
    "math.floor",
    "math.ceil",
];

/// Longest list `range` may build, so a template cannot exhaust memory.
const MAX_RANGE: i64 = 1_000_000;

pub(super) fn constant(name: &str) -> Option<f64> {
    match name {
        "math.pi" => Some(std::f64::consts::PI),
        "math.e" => Some(std::f64::consts::E),
        "math.tau" => Some(std::f64::consts::TAU),
        _ => None,
    }
}

pub(super) fn callable(name: &str) -> Option<&'static str> {
    FUNCTIONS
        .iter()
        .find(|f| **f == name)
        .map(|f| f.strip_prefix("math.").unwrap_or(f))
}

pub(super) fn binary(op: &str) -> &'static str {
    match op {
        "+" => "add",
        "-" => "sub",
        "*" => "mul",
        "/" => "truediv",
        "//" => "floordiv",
        "%" => "mod",
        _ => "pow",
    }
}

pub(super) fn comparison(op: &str) -> &'static str {
    match op {
        "==" => "eq",
        "!=" => "ne",
        "<" => "lt",
        "<=" => "le",
        ">" => "gt",
        ">=" => "ge",
        "in" => "in",
        _ => "not_in",
    }
}

/// Python truthiness: `0`, `0.0`, `""`, `[]`, `False` and `None` are false.
pub(crate) fn truthy(value: &Value) -> bool {
    match value {
        Value::Boolean(b) => *b,
        Value::Int(n) => *n != 0,
        Value::Float(x) => *x != 0.0,
        Value::String(s) => !s.is_empty(),
        Value::Tuple(items) => !items.is_empty(),
        Value::Empty => false,
    }
}

fn fail<T>(message: impl Into<String>) -> EvalexprResult<T> {
    Err(EvalexprError::CustomMessage(message.into()))
}

fn type_name(value: &Value) -> &'static str {
    match value {
        Value::String(_) => "str",
        Value::Float(_) => "float",
        Value::Int(_) => "int",
        Value::Boolean(_) => "bool",
        Value::Tuple(_) => "list",
        Value::Empty => "None",
    }
}

#[derive(Clone, Copy)]
enum Num {
    Int(i64),
    Float(f64),
}

fn num(value: &Value) -> Option<Num> {
    match value {
        Value::Int(n) => Some(Num::Int(*n)),
        Value::Float(x) => Some(Num::Float(*x)),
        Value::Boolean(b) => Some(Num::Int(i64::from(*b))),
        _ => None,
    }
}

fn float(n: Num) -> f64 {
    match n {
        Num::Int(i) => i as f64,
        Num::Float(x) => x,
    }
}

fn numbers(op: &str, a: &Value, b: &Value) -> EvalexprResult<(Num, Num)> {
    match (num(a), num(b)) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => fail(format!(
            "unsupported operand types for {op}: '{}' and '{}'",
            type_name(a),
            type_name(b)
        )),
    }
}

fn overflow<T>(op: &str) -> EvalexprResult<T> {
    fail(format!("integer overflow in {op}"))
}

/// Applies an integer operation when both are ints, else the float one.
fn arithmetic(
    op: &str,
    a: &Value,
    b: &Value,
    ints: fn(i64, i64) -> Option<i64>,
    floats: fn(f64, f64) -> f64,
) -> EvalexprResult<Value> {
    match numbers(op, a, b)? {
        (Num::Int(x), Num::Int(y)) => ints(x, y).map(Value::Int).map_or_else(|| overflow(op), Ok),
        (x, y) => Ok(Value::Float(floats(float(x), float(y)))),
    }
}

fn arity<'a, const N: usize>(name: &str, args: &'a [Value]) -> EvalexprResult<&'a [Value; N]> {
    args.try_into().or_else(|_| {
        fail(format!(
            "{name}() takes {N} argument(s), got {}",
            args.len()
        ))
    })
}

/// The operation or builtin `name` (as [`binary`], [`comparison`] and [`callable`] name them)
/// applied to `args`.
pub(super) fn apply(name: &str, args: &[Value]) -> EvalexprResult<Value> {
    match name {
        "list" | "tuple" => {
            items(&arity::<1>(name, args)?[0]).map(|items| Value::Tuple(items.to_vec()))
        }
        "neg" => negate(&arity::<1>(name, args)?[0]),
        "add" => add(arity::<2>(name, args)?),
        "sub" => {
            let [a, b] = arity::<2>(name, args)?;
            arithmetic("-", a, b, i64::checked_sub, |x, y| x - y)
        }
        "mul" => multiply(arity::<2>(name, args)?),
        "truediv" => true_divide(arity::<2>(name, args)?),
        "floordiv" => floor_divide(arity::<2>(name, args)?),
        "mod" => modulo(arity::<2>(name, args)?),
        "pow" => power(arity::<2>(name, args)?),
        "eq" => Ok(Value::Boolean(equal(arity::<2>(name, args)?))),
        "ne" => Ok(Value::Boolean(!equal(arity::<2>(name, args)?))),
        "lt" | "le" | "gt" | "ge" => compare(name, arity::<2>(name, args)?),
        "in" => contains(arity::<2>(name, args)?).map(Value::Boolean),
        "not_in" => contains(arity::<2>(name, args)?).map(|found| Value::Boolean(!found)),
        "index" => index(arity::<2>(name, args)?),
        "slice" => slice(arity::<3>(name, args)?),
        _ => builtin(name, args),
    }
}

fn negate(value: &Value) -> EvalexprResult<Value> {
    match num(value) {
        Some(Num::Int(n)) => n
            .checked_neg()
            .map(Value::Int)
            .map_or_else(|| overflow("-"), Ok),
        Some(Num::Float(x)) => Ok(Value::Float(-x)),
        None => fail(format!(
            "bad operand type for unary -: '{}'",
            type_name(value)
        )),
    }
}

fn true_divide([a, b]: &[Value; 2]) -> EvalexprResult<Value> {
    let (x, y) = numbers("/", a, b)?;
    if float(y) == 0.0 {
        return fail("division by zero");
    }
    Ok(Value::Float(float(x) / float(y)))
}

/// Python's `//`: rounds towards negative infinity.
fn floor_divide([a, b]: &[Value; 2]) -> EvalexprResult<Value> {
    if num(b).is_some_and(|y| float(y) == 0.0) {
        return fail("integer division or modulo by zero");
    }
    arithmetic(
        "//",
        a,
        b,
        |x, y| {
            x.checked_div_euclid(y)
                .map(|q| if y < 0 && x % y != 0 { q + 1 } else { q })
        },
        |x, y| (x / y).floor(),
    )
}

/// Python's `%`: the result has the divisor's sign.
fn modulo([a, b]: &[Value; 2]) -> EvalexprResult<Value> {
    if num(b).is_some_and(|y| float(y) == 0.0) {
        return fail("integer division or modulo by zero");
    }
    arithmetic(
        "%",
        a,
        b,
        |x, y| {
            x.checked_rem(y).map(|r| {
                if r != 0 && (r < 0) != (y < 0) {
                    r + y
                } else {
                    r
                }
            })
        },
        |x, y| {
            let r = x % y;
            if r != 0.0 && (r < 0.0) != (y < 0.0) {
                r + y
            } else {
                r
            }
        },
    )
}

fn power([a, b]: &[Value; 2]) -> EvalexprResult<Value> {
    match numbers("**", a, b)? {
        (Num::Int(x), Num::Int(y)) if y >= 0 => u32::try_from(y)
            .ok()
            .and_then(|y| x.checked_pow(y))
            .map(Value::Int)
            .map_or_else(|| overflow("**"), Ok),
        (x, y) => Ok(Value::Float(float(x).powf(float(y)))),
    }
}

fn builtin(name: &str, args: &[Value]) -> EvalexprResult<Value> {
    match name {
        "len" => match &arity::<1>(name, args)?[0] {
            Value::String(s) => Ok(Value::Int(s.chars().count() as i64)),
            Value::Tuple(items) => Ok(Value::Int(items.len() as i64)),
            other => fail(format!(
                "object of type '{}' has no len()",
                type_name(other)
            )),
        },
        "range" => range(args),
        "abs" => match num(&arity::<1>(name, args)?[0]) {
            Some(Num::Int(n)) => n
                .checked_abs()
                .map(Value::Int)
                .map_or_else(|| overflow("abs"), Ok),
            Some(Num::Float(x)) => Ok(Value::Float(x.abs())),
            None => fail(format!(
                "bad operand type for abs(): '{}'",
                type_name(&args[0])
            )),
        },
        "min" | "max" => extreme(name, args),
        "sum" => items(&arity::<1>(name, args)?[0])?
            .iter()
            .try_fold(Value::Int(0), |total, item| add(&[total, item.clone()])),
        "round" => round(args),
        "int" | "float" => convert(name, &arity::<1>(name, args)?[0]),
        "str" => Ok(Value::String(crate::value::format_value(
            &arity::<1>(name, args)?[0],
        ))),
        "bool" => Ok(Value::Boolean(truthy(&arity::<1>(name, args)?[0]))),
        "atan2" => {
            let [y, x] = arity::<2>(name, args)?;
            let (y, x) = numbers("atan2", y, x)?;
            Ok(Value::Float(float(y).atan2(float(x))))
        }
        _ => math(name, args),
    }
}

/// `int(value)` or `float(value)`.
fn convert(name: &str, value: &Value) -> EvalexprResult<Value> {
    match (name, value) {
        ("int", Value::String(s)) => s
            .trim()
            .parse()
            .map(Value::Int)
            .or_else(|_| fail(format!("invalid literal for int(): {s:?}"))),
        ("int", other) => match num(other) {
            Some(Num::Float(x)) if x.is_finite() && x.abs() < 9.2e18 => {
                Ok(Value::Int(x.trunc() as i64))
            }
            Some(Num::Int(n)) => Ok(Value::Int(n)),
            _ => fail(format!("int() cannot convert '{}'", type_name(other))),
        },
        (_, Value::String(s)) => s
            .trim()
            .parse()
            .map(Value::Float)
            .or_else(|_| fail(format!("could not convert string to float: {s:?}"))),
        (_, other) => num(other).map(|n| Value::Float(float(n))).map_or_else(
            || fail(format!("float() cannot convert '{}'", type_name(other))),
            Ok,
        ),
    }
}

fn math(name: &str, args: &[Value]) -> EvalexprResult<Value> {
    let function: fn(f64) -> f64 = match name {
        "sqrt" => f64::sqrt,
        "sin" => f64::sin,
        "cos" => f64::cos,
        "tan" => f64::tan,
        "asin" => f64::asin,
        "acos" => f64::acos,
        "atan" => f64::atan,
        "radians" => f64::to_radians,
        "degrees" => f64::to_degrees,
        "floor" | "ceil" => {
            let value = &arity::<1>(name, args)?[0];
            let x = num(value)
                .map(float)
                .map_or_else(|| fail(format!("math.{name}() needs a number")), Ok)?;
            let rounded = if name == "floor" { x.floor() } else { x.ceil() };
            return if rounded.is_finite() && rounded.abs() < 9.2e18 {
                Ok(Value::Int(rounded as i64))
            } else {
                fail(format!("cannot convert {x} to an integer"))
            };
        }
        _ => return fail(format!("function `{name}` is not defined")),
    };
    let value = &arity::<1>(name, args)?[0];
    let x = num(value).map(float).map_or_else(
        || {
            fail(format!(
                "math.{name}() needs a number, got '{}'",
                type_name(value)
            ))
        },
        Ok,
    )?;
    let y = function(x);
    if y.is_nan() && !x.is_nan() {
        return fail(format!("math domain error in math.{name}({x})"));
    }
    Ok(Value::Float(y))
}

fn items(value: &Value) -> EvalexprResult<&[Value]> {
    match value {
        Value::Tuple(items) => Ok(items),
        other => fail(format!("'{}' object is not iterable", type_name(other))),
    }
}

fn add([a, b]: &[Value; 2]) -> EvalexprResult<Value> {
    match (a, b) {
        (Value::String(x), Value::String(y)) => Ok(Value::String(format!("{x}{y}"))),
        (Value::Tuple(x), Value::Tuple(y)) => {
            Ok(Value::Tuple(x.iter().chain(y).cloned().collect()))
        }
        _ => arithmetic("+", a, b, i64::checked_add, |x, y| x + y),
    }
}

fn multiply([a, b]: &[Value; 2]) -> EvalexprResult<Value> {
    let repeat = |count: i64| -> EvalexprResult<usize> {
        usize::try_from(count.max(0))
            .ok()
            .filter(|n| *n <= MAX_RANGE as usize)
            .map_or_else(|| fail("repetition too long"), Ok)
    };
    match (a, b) {
        (Value::String(s), Value::Int(n)) | (Value::Int(n), Value::String(s)) => {
            Ok(Value::String(s.repeat(repeat(*n)?)))
        }
        (Value::Tuple(t), Value::Int(n)) | (Value::Int(n), Value::Tuple(t)) => {
            let count = repeat(*n)?;
            if t.len().saturating_mul(count) > MAX_RANGE as usize {
                return fail("repetition too long");
            }
            Ok(Value::Tuple(
                t.iter().cloned().cycle().take(t.len() * count).collect(),
            ))
        }
        _ => arithmetic("*", a, b, i64::checked_mul, |x, y| x * y),
    }
}

fn equal([a, b]: &[Value; 2]) -> bool {
    match (num(a), num(b)) {
        (Some(Num::Int(x)), Some(Num::Int(y))) => x == y,
        (Some(x), Some(y)) => float(x) == float(y),
        _ => match (a, b) {
            (Value::Tuple(x), Value::Tuple(y)) => {
                x.len() == y.len() && x.iter().zip(y).all(|(p, q)| equal(&[p.clone(), q.clone()]))
            }
            _ => a == b,
        },
    }
}

fn compare(op: &str, [a, b]: &[Value; 2]) -> EvalexprResult<Value> {
    let ordering = match (a, b) {
        (Value::String(x), Value::String(y)) => x.partial_cmp(y),
        _ => {
            let symbol = match op {
                "lt" => "<",
                "le" => "<=",
                "gt" => ">",
                _ => ">=",
            };
            let (x, y) = numbers(symbol, a, b)?;
            match (x, y) {
                (Num::Int(x), Num::Int(y)) => x.partial_cmp(&y),
                (x, y) => float(x).partial_cmp(&float(y)),
            }
        }
    };
    use std::cmp::Ordering::{Equal, Greater, Less};
    Ok(Value::Boolean(matches!(
        (op, ordering),
        ("lt", Some(Less))
            | ("le", Some(Less | Equal))
            | ("gt", Some(Greater))
            | ("ge", Some(Greater | Equal))
    )))
}

fn contains([item, container]: &[Value; 2]) -> EvalexprResult<bool> {
    match (item, container) {
        (Value::String(needle), Value::String(haystack)) => Ok(haystack.contains(needle.as_str())),
        (_, Value::Tuple(items)) => Ok(items.iter().any(|x| equal(&[item.clone(), x.clone()]))),
        (_, other) => fail(format!(
            "argument of type '{}' is not iterable",
            type_name(other)
        )),
    }
}

fn position(index: &Value, len: usize) -> EvalexprResult<Option<usize>> {
    let Value::Int(i) = index else {
        return fail(format!(
            "indices must be integers, not '{}'",
            type_name(index)
        ));
    };
    let len = len as i64;
    let i = if *i < 0 { i + len } else { *i };
    Ok(usize::try_from(i).ok().filter(|_| i < len))
}

fn index([target, at]: &[Value; 2]) -> EvalexprResult<Value> {
    match target {
        Value::Tuple(items) => match position(at, items.len())? {
            Some(i) => Ok(items[i].clone()),
            None => fail(format!(
                "list index {} out of range (length {})",
                crate::value::format_value(at),
                items.len()
            )),
        },
        Value::String(s) => {
            let chars: Vec<char> = s.chars().collect();
            match position(at, chars.len())? {
                Some(i) => Ok(Value::String(chars[i].to_string())),
                None => fail(format!(
                    "string index {} out of range",
                    crate::value::format_value(at)
                )),
            }
        }
        other => fail(format!(
            "'{}' object is not subscriptable",
            type_name(other)
        )),
    }
}

fn slice([target, start, end]: &[Value; 3]) -> EvalexprResult<Value> {
    let bound = |value: &Value, len: usize, default: usize| -> EvalexprResult<usize> {
        match value {
            Value::Empty => Ok(default),
            Value::Int(i) => {
                let len = len as i64;
                let i = if *i < 0 {
                    (i + len).max(0)
                } else {
                    (*i).min(len)
                };
                Ok(i as usize)
            }
            other => fail(format!(
                "slice indices must be integers, not '{}'",
                type_name(other)
            )),
        }
    };
    match target {
        Value::Tuple(items) => {
            let (a, b) = (
                bound(start, items.len(), 0)?,
                bound(end, items.len(), items.len())?,
            );
            Ok(Value::Tuple(if a < b {
                items[a..b].to_vec()
            } else {
                Vec::new()
            }))
        }
        Value::String(s) => {
            let chars: Vec<char> = s.chars().collect();
            let (a, b) = (
                bound(start, chars.len(), 0)?,
                bound(end, chars.len(), chars.len())?,
            );
            Ok(Value::String(if a < b {
                chars[a..b].iter().collect()
            } else {
                String::new()
            }))
        }
        other => fail(format!(
            "'{}' object is not subscriptable",
            type_name(other)
        )),
    }
}

fn range(args: &[Value]) -> EvalexprResult<Value> {
    let ints: Vec<i64> = args
        .iter()
        .map(|a| match a {
            Value::Int(n) => Ok(*n),
            other => fail(format!(
                "'{}' object cannot be interpreted as an integer",
                type_name(other)
            )),
        })
        .collect::<EvalexprResult<_>>()?;
    let (start, stop, step) = match ints[..] {
        [stop] => (0, stop, 1),
        [start, stop] => (start, stop, 1),
        [start, stop, step] => (start, stop, step),
        _ => {
            return fail(format!(
                "range() takes 1 to 3 arguments, got {}",
                args.len()
            ));
        }
    };
    if step == 0 {
        return fail("range() arg 3 must not be zero");
    }
    let (span, stride) = (i128::from(stop) - i128::from(start), i128::from(step));
    let count = if (span > 0) == (stride > 0) && span != 0 {
        (span.abs() + stride.abs() - 1) / stride.abs()
    } else {
        0
    };
    if count > i128::from(MAX_RANGE) {
        return fail(format!(
            "range() of {count} items is longer than {MAX_RANGE}"
        ));
    }
    Ok(Value::Tuple(
        (0..count as i64)
            .map(|i| Value::Int(start + i * step))
            .collect(),
    ))
}

fn extreme(name: &str, args: &[Value]) -> EvalexprResult<Value> {
    let candidates = if let [single] = args {
        items(single)?
    } else {
        args
    };
    let mut best: Option<&Value> = None;
    for candidate in candidates {
        best = Some(match best {
            None => candidate,
            Some(current) => {
                let op = if name == "min" { "lt" } else { "gt" };
                if compare(op, &[candidate.clone(), current.clone()])? == Value::Boolean(true) {
                    candidate
                } else {
                    current
                }
            }
        });
    }
    best.cloned()
        .map_or_else(|| fail(format!("{name}() arg is an empty sequence")), Ok)
}

fn round(args: &[Value]) -> EvalexprResult<Value> {
    let (value, digits) = match args {
        [value] => (value, None),
        [value, Value::Int(digits)] => (value, Some(*digits)),
        _ => return fail("round() takes a number and optional integer digits"),
    };
    let x = match num(value) {
        Some(Num::Int(n)) => return Ok(Value::Int(n)),
        Some(Num::Float(x)) => x,
        None => {
            return fail(format!(
                "round() needs a number, got '{}'",
                type_name(value)
            ));
        }
    };
    match digits {
        None if x.is_finite() && x.abs() < 9.2e18 => Ok(Value::Int(x.round_ties_even() as i64)),
        None => fail(format!("cannot round {x} to an integer")),
        Some(d) => {
            let scale = 10f64.powi(d.clamp(-300, 300) as i32);
            Ok(Value::Float((x * scale).round_ties_even() / scale))
        }
    }
}
