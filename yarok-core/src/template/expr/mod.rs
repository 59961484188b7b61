//! Template expressions: a Python subset, evaluated by evalexpr.
//!
//! The original's templates use Python expressions (`0.5 + 0.082*x if z % 2 == 0 else 0.58`,
//! `range(n)`, `lst[0]`). They are parsed here and lowered to evalexpr code in which every
//! operation whose meaning differs between Python and evalexpr (true division, `%` and `//` on
//! negatives, `==` across int and float, indexing, lists, calls) is a `py::` function, so results
//! match Python's. `a if c else b` evaluates only the branch taken. Evaluation is sandboxed: the
//! only functions are the pure ones listed in [`FUNCTIONS`], evalexpr's builtins are disabled and
//! nothing can assign.

mod functions;
mod lexer;
mod parser;

use std::fmt;

use evalexpr::{Context, EvalexprResult, Node, Value as Inner};
pub use functions::FUNCTIONS;
pub(crate) use functions::truthy;
use parser::Ast;

use crate::value::{Value, format_value};

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

    fn eval(error: &evalexpr::EvalexprError) -> Self {
        let message = match error {
            evalexpr::EvalexprError::VariableIdentifierNotFound(name) => {
                format!("name `{name}` is not defined")
            }
            evalexpr::EvalexprError::CustomMessage(message) => message.clone(),
            other => other.to_string(),
        };
        Self {
            offset: None,
            message,
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
    plan: Plan,
}

/// evalexpr code plus the conditionals lifted out of it, each bound to a temporary variable and
/// evaluated lazily before the code runs.
#[derive(Debug, Clone)]
struct Plan {
    code: Node,
    conditionals: Vec<Conditional>,
}

#[derive(Debug, Clone)]
struct Conditional {
    variable: String,
    condition: Plan,
    then: Plan,
    otherwise: Plan,
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
        let mut temporaries = 0;
        Ok(Self {
            plan: plan(&ast, &mut temporaries)?,
        })
    }

    /// Evaluates the expression with `variables` in scope.
    ///
    /// # Errors
    ///
    /// An [`ExprError`] for an unknown name, a type error, a division by zero, …
    pub fn eval(&self, variables: &dyn Variables) -> Result<Value, ExprError> {
        let mut scope = Scope {
            variables,
            temporaries: Vec::new(),
        };
        self.plan.eval(&mut scope).map(Value)
    }
}

impl Plan {
    fn eval(&self, scope: &mut Scope<'_>) -> Result<Inner, ExprError> {
        for conditional in &self.conditionals {
            let condition = conditional.condition.eval(scope)?;
            let branch = if functions::truthy(&condition) {
                &conditional.then
            } else {
                &conditional.otherwise
            };
            let value = branch.eval(scope)?;
            scope
                .temporaries
                .push((conditional.variable.clone(), value));
        }
        let result = self
            .code
            .eval_with_context(scope)
            .map_err(|e| ExprError::eval(&e));
        let bound = scope.temporaries.len() - self.conditionals.len();
        scope.temporaries.truncate(bound);
        result
    }
}

fn plan(ast: &Ast, temporaries: &mut usize) -> Result<Plan, ExprError> {
    let mut emitter = Emitter {
        code: String::new(),
        conditionals: Vec::new(),
        temporaries,
    };
    emitter.emit(ast)?;
    let code = evalexpr::build_operator_tree(&emitter.code).map_err(|e| ExprError {
        offset: None,
        message: format!("internal: {e} in {}", emitter.code),
    })?;
    Ok(Plan {
        code,
        conditionals: emitter.conditionals,
    })
}

/// Writes evalexpr code for an [`Ast`], lifting conditionals out into lazily evaluated plans.
struct Emitter<'a> {
    code: String,
    conditionals: Vec<Conditional>,
    temporaries: &'a mut usize,
}

impl Emitter<'_> {
    fn call(&mut self, name: &str, args: &[&Ast]) -> Result<(), ExprError> {
        self.code.push_str(&format!("py::{name}({}", args.len()));
        for arg in args {
            self.code.push_str(", ");
            self.emit(arg)?;
        }
        self.code.push(')');
        Ok(())
    }

    fn emit(&mut self, ast: &Ast) -> Result<(), ExprError> {
        match ast {
            Ast::Int(n) => self.code.push_str(&n.to_string()),
            Ast::Float(x) => self.code.push_str(&float_literal(*x)),
            Ast::Str(s) => self.code.push_str(&format!(
                "\"{}\"",
                s.replace('\\', "\\\\").replace('"', "\\\"")
            )),
            Ast::Bool(b) => self.code.push_str(if *b { "true" } else { "false" }),
            Ast::None => self.code.push_str("py::none(0)"),
            Ast::Name(name) => match functions::constant(name) {
                Some(value) => self.code.push_str(&float_literal(value)),
                None if name.contains('.') => {
                    return Err(ExprError {
                        offset: None,
                        message: format!("name `{name}` is not defined"),
                    });
                }
                None => self.code.push_str(name),
            },
            Ast::List(items) => self.call("literal", &items.iter().collect::<Vec<_>>())?,
            Ast::Neg(value) => self.call("neg", &[value])?,
            Ast::Not(value) => self.call("not", &[value])?,
            Ast::Binary(op, left, right) => self.call(functions::binary(op), &[left, right])?,
            Ast::Compare(operands, operators) => {
                self.code.push('(');
                for (i, op) in operators.iter().enumerate() {
                    if i > 0 {
                        self.code.push_str(" && ");
                    }
                    self.call(functions::comparison(op), &[&operands[i], &operands[i + 1]])?;
                }
                self.code.push(')');
            }
            Ast::Chain(first, rest) => {
                self.code
                    .push_str(&format!("py::chain({}, ", 1 + 2 * rest.len()));
                self.emit(first)?;
                for (op, operand) in rest {
                    self.code
                        .push_str(&format!(", \"{}\", ", functions::binary(op)));
                    self.emit(operand)?;
                }
                self.code.push(')');
            }
            Ast::And(operands) => self.call("and", &operands.iter().collect::<Vec<_>>())?,
            Ast::Or(operands) => self.call("or", &operands.iter().collect::<Vec<_>>())?,
            Ast::If {
                condition,
                then,
                otherwise,
            } => {
                let variable = format!("py::t{}", *self.temporaries);
                *self.temporaries += 1;
                let conditional = Conditional {
                    variable: variable.clone(),
                    condition: plan(condition, self.temporaries)?,
                    then: plan(then, self.temporaries)?,
                    otherwise: plan(otherwise, self.temporaries)?,
                };
                self.conditionals.push(conditional);
                self.code.push_str(&variable);
            }
            Ast::Call(name, args) => {
                let function = functions::callable(name).ok_or_else(|| ExprError {
                    offset: None,
                    message: format!("function `{name}` is not defined"),
                })?;
                self.call(function, &args.iter().collect::<Vec<_>>())?;
            }
            Ast::Index(target, index) => self.call("index", &[target, index])?,
            Ast::Slice(target, start, end) => {
                let none = Ast::None;
                let start = start.as_deref().unwrap_or(&none);
                let end = end.as_deref().unwrap_or(&none);
                self.call("slice", &[target, start, end])?;
            }
        }
        Ok(())
    }
}

/// A float literal evalexpr reads back exactly and never as an integer.
fn float_literal(x: f64) -> String {
    let text = format!("{x}");
    if text.contains('.') {
        text
    } else {
        format!("{text}.0")
    }
}

struct Scope<'a> {
    variables: &'a dyn Variables,
    temporaries: Vec<(String, Inner)>,
}

impl Context for Scope<'_> {
    fn get_value(&self, identifier: &str) -> Option<&Inner> {
        if identifier.starts_with("py::") {
            return self
                .temporaries
                .iter()
                .rev()
                .find(|(name, _)| name == identifier)
                .map(|(_, v)| v);
        }
        self.variables.get(identifier).map(|value| &value.0)
    }

    fn call_function(&self, identifier: &str, argument: &Inner) -> EvalexprResult<Inner> {
        functions::call(identifier, argument)
    }

    fn are_builtin_functions_disabled(&self) -> bool {
        true
    }

    fn set_builtin_functions_disabled(&mut self, _disabled: bool) -> EvalexprResult<()> {
        Ok(())
    }
}

#[cfg(test)]
mod tests;
