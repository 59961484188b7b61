//! Evaluation of a parsed expression, node by node, with Python's meaning for every operation
//! ([`functions`](super::functions)). `a if c else b` evaluates only the branch taken; `and`,
//! `or` and chained comparisons stop at the first operand that decides them, as Python's do.

use evalexpr::Value as Inner;

use super::functions::{self, truthy};
use super::parser::Ast;
use super::{ExprError, Variables};

/// The value of `ast` with `variables` in scope.
pub(super) fn evaluate(ast: &Ast, variables: &dyn Variables) -> Result<Inner, ExprError> {
    Evaluator { variables }.value(ast)
}

struct Evaluator<'a> {
    variables: &'a dyn Variables,
}

impl Evaluator<'_> {
    fn value(&self, ast: &Ast) -> Result<Inner, ExprError> {
        match ast {
            Ast::Int(n) => Ok(Inner::Int(*n)),
            Ast::Float(x) => Ok(Inner::Float(*x)),
            Ast::Str(s) => Ok(Inner::String(s.clone())),
            Ast::Bool(b) => Ok(Inner::Boolean(*b)),
            Ast::None => Ok(Inner::Empty),
            Ast::Name(name) => self.variable(name),
            Ast::List(items) => Ok(Inner::Tuple(self.values(items)?)),
            Ast::Neg(operand) => apply("neg", vec![self.value(operand)?]),
            Ast::Not(operand) => Ok(Inner::Boolean(!truthy(&self.value(operand)?))),
            Ast::Binary(op, left, right) => apply(
                functions::binary(op),
                vec![self.value(left)?, self.value(right)?],
            ),
            Ast::Chain(first, rest) => rest
                .iter()
                .try_fold(self.value(first)?, |left, (op, right)| {
                    apply(functions::binary(op), vec![left, self.value(right)?])
                }),
            Ast::Compare(operands, operators) => self.compare(operands, operators),
            Ast::And(operands) => self.deciding(operands, false),
            Ast::Or(operands) => self.deciding(operands, true),
            Ast::If {
                condition,
                then,
                otherwise,
            } => match truthy(&self.value(condition)?) {
                true => self.value(then),
                false => self.value(otherwise),
            },
            Ast::Call(function, args) => apply(function, self.values(args)?),
            Ast::Index(target, index) => {
                apply("index", vec![self.value(target)?, self.value(index)?])
            }
            Ast::Slice(target, start, end) => {
                let bound = |bound: &Option<Box<Ast>>| match bound {
                    Some(bound) => self.value(bound),
                    None => Ok(Inner::Empty),
                };
                apply(
                    "slice",
                    vec![self.value(target)?, bound(start)?, bound(end)?],
                )
            }
        }
    }

    fn values(&self, asts: &[Ast]) -> Result<Vec<Inner>, ExprError> {
        asts.iter().map(|ast| self.value(ast)).collect()
    }

    fn variable(&self, name: &str) -> Result<Inner, ExprError> {
        match self.variables.get(name) {
            Some(value) => Ok(value.0.clone()),
            None => Err(ExprError::evaluating(format!(
                "name `{name}` is not defined"
            ))),
        }
    }

    /// `a < b <= c`: each comparison in turn, each operand evaluated once, until one is false.
    fn compare(&self, operands: &[Ast], operators: &[&str]) -> Result<Inner, ExprError> {
        let Some((first, rest)) = operands.split_first() else {
            return Ok(Inner::Empty);
        };
        let mut left = self.value(first)?;
        for (operator, right) in operators.iter().zip(rest) {
            let right = self.value(right)?;
            let holds = apply(functions::comparison(operator), vec![left, right.clone()])?;
            if !truthy(&holds) {
                return Ok(Inner::Boolean(false));
            }
            left = right;
        }
        Ok(Inner::Boolean(true))
    }

    /// `and` (`truth` false) or `or` (`truth` true): the first operand whose truth is `truth`,
    /// or else the last.
    fn deciding(&self, operands: &[Ast], truth: bool) -> Result<Inner, ExprError> {
        let Some((last, deciding)) = operands.split_last() else {
            return Ok(Inner::Empty);
        };
        for operand in deciding {
            let value = self.value(operand)?;
            if truthy(&value) == truth {
                return Ok(value);
            }
        }
        self.value(last)
    }
}

fn apply(function: &str, args: Vec<Inner>) -> Result<Inner, ExprError> {
    functions::apply(function, &args).map_err(|e| ExprError::eval(&e))
}
