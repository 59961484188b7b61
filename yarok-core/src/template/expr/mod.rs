//! Template expressions: a Python subset, parsed into a syntax tree and evaluated from
//! it.
//!
//! The original's templates use Python expressions (`0.5 + 0.082*x if z % 2 == 0 else 0.58`,
//! `range(n)`, `lst[0]`). Values are evalexpr's; every operation has Python's meaning (true
//! division, `%` and `//` on negatives, `==` across int and float, indexing, slicing), so results
//! match Python's. `a if c else b`, `and`, `or` and chained comparisons evaluate only what decides
//! them. Evaluation is sandboxed: the only functions are the pure ones listed in [`FUNCTIONS`],
//! and nothing can assign.

mod eval;
mod functions;
mod lexer;
mod parser;

use std::fmt;

pub use functions::FUNCTIONS;
pub(crate) use functions::truthy;
use parser::Ast;

use crate::value::Value;

/// Names visible to an expression: config values and loop variables.
pub trait Variables {
    /// The value bound to `name`, if any.
    fn get(&self, name: &str) -> Option<&Value>;
}

/// An expression could not be parsed or evaluated.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExprError {
    /// Character offset in the expression where parsing failed (`None` for evaluation errors).
    pub offset: Option<usize>,
    /// What went wrong.
    pub message: String,
}

impl ExprError {
    fn at(offset: usize, message: impl Into<String>) -> Self {
        Self {
            offset: Some(offset),
            message: message.into(),
        }
    }

    fn evaluating(message: impl Into<String>) -> Self {
        Self {
            offset: None,
            message: message.into(),
        }
    }

    fn eval(error: &evalexpr::EvalexprError) -> Self {
        match error {
            evalexpr::EvalexprError::CustomMessage(message) => Self::evaluating(message.clone()),
            other => Self::evaluating(other.to_string()),
        }
    }
}

impl fmt::Display for ExprError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.offset {
            Some(offset) => write!(f, "{} (at character {})", self.message, offset + 1),
            None => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for ExprError {}

/// A parsed expression, ready to be evaluated many times.
#[derive(Debug, Clone)]
pub struct Expr {
    ast: Ast,
}

/// Whether `name` can name a variable in an expression (a loop's `as`): a single name, not a
/// keyword or constant.
pub(crate) fn is_variable_name(name: &str) -> bool {
    matches!(
        lexer::tokenize(name).as_deref(),
        Ok([(lexer::Token::Name(word), _)]) if !parser::KEYWORDS.contains(&word.as_str())
    )
}

impl Expr {
    /// Parses a Python expression.
    ///
    /// # Errors
    ///
    /// An [`ExprError`] with the offending character offset.
    pub fn parse(source: &str) -> Result<Self, ExprError> {
        let tokens = lexer::tokenize(source)?;
        let ast = parser::parse(&tokens, source.chars().count())?;
        Ok(Self { ast })
    }

    /// Evaluates the expression with `variables` in scope.
    ///
    /// # Errors
    ///
    /// An [`ExprError`] for an unknown name, a type error, a division by zero, a result that is
    /// not a finite number (NaN, an infinity), …
    pub fn eval(&self, variables: &dyn Variables) -> Result<Value, ExprError> {
        let value = eval::evaluate(&self.ast, variables)?;
        if let Some(number) = not_finite(&value) {
            return Err(ExprError::evaluating(format!(
                "the expression gives {number}, not a finite number a model can hold: look for a \
                 division by zero, a power of zero below zero, or a nan or inf"
            )));
        }
        Ok(Value(value))
    }
}

/// The first number in `value` (itself, or an item of a list) that is NaN or infinite.
fn not_finite(value: &evalexpr::Value) -> Option<f64> {
    match value {
        evalexpr::Value::Float(number) if !number.is_finite() => Some(*number),
        evalexpr::Value::Tuple(items) => items.iter().find_map(not_finite),
        _ => None,
    }
}

#[cfg(test)]
mod tests;
