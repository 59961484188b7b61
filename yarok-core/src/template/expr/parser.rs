//! Parses the Python expression subset into an [`Ast`].

use super::lexer::{Spanned, Token};
use super::{ExprError, functions};

/// Nesting deeper than this is refused, so hostile input cannot overflow the stack.
const MAX_DEPTH: usize = 64;

#[derive(Debug, Clone, PartialEq)]
pub(super) enum Ast {
    Int(i64),
    Float(f64),
    Str(String),
    Bool(bool),
    None,
    Name(String),
    List(Vec<Ast>),
    Neg(Box<Ast>),
    Not(Box<Ast>),
    Binary(&'static str, Box<Ast>, Box<Ast>),
    /// `a + b - c` or `a * b / c`: left-associative operations kept flat, so that a long chain
    /// needs no deep recursion to evaluate or drop.
    Chain(Box<Ast>, Vec<(&'static str, Ast)>),
    /// `a < b <= c`: operands and the operators between them.
    Compare(Vec<Ast>, Vec<&'static str>),
    /// `a and b and c`, flat.
    And(Vec<Ast>),
    /// `a or b or c`, flat.
    Or(Vec<Ast>),
    If {
        condition: Box<Ast>,
        then: Box<Ast>,
        otherwise: Box<Ast>,
    },
    /// A call of one of [`FUNCTIONS`](super::FUNCTIONS), by the name `functions::apply` knows.
    Call(&'static str, Vec<Ast>),
    Index(Box<Ast>, Box<Ast>),
    Slice(Box<Ast>, Option<Box<Ast>>, Option<Box<Ast>>),
}

/// The words that cannot name a variable: the constants and the keywords.
pub(super) const KEYWORDS: [&str; 12] = [
    "True", "False", "None", "if", "else", "and", "or", "not", "in", "lambda", "for", "import",
];

pub(super) fn parse(tokens: &[Spanned], source_len: usize) -> Result<Ast, ExprError> {
    let mut parser = Parser {
        tokens,
        at: 0,
        depth: 0,
        source_len,
    };
    let ast = parser.conditional()?;
    match parser.tokens.get(parser.at) {
        None => Ok(ast),
        Some((token, offset)) => Err(ExprError::at(
            *offset,
            format!("unexpected {}", describe(token)),
        )),
    }
}

struct Parser<'a> {
    tokens: &'a [Spanned],
    at: usize,
    depth: usize,
    source_len: usize,
}

fn describe(token: &Token) -> String {
    match token {
        Token::Int(n) => format!("number {n}"),
        Token::Float(x) => format!("number {x}"),
        Token::Str(s) => format!("string {s:?}"),
        Token::Name(n) => format!("`{n}`"),
        Token::Op(op) => format!("`{op}`"),
    }
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.at).map(|(token, _)| token)
    }

    fn offset(&self) -> usize {
        self.tokens
            .get(self.at)
            .map_or(self.source_len, |(_, offset)| *offset)
    }

    fn is_op(&self, op: &str) -> bool {
        matches!(self.peek(), Some(Token::Op(o)) if *o == op)
    }

    fn is_keyword(&self, word: &str) -> bool {
        matches!(self.peek(), Some(Token::Name(n)) if n == word)
    }

    fn eat_op(&mut self, op: &str) -> bool {
        let found = self.is_op(op);
        self.at += usize::from(found);
        found
    }

    fn eat_keyword(&mut self, word: &str) -> bool {
        let found = self.is_keyword(word);
        self.at += usize::from(found);
        found
    }

    fn expect_op(&mut self, op: &str) -> Result<(), ExprError> {
        if self.eat_op(op) {
            return Ok(());
        }
        let found = self.peek().map_or_else(|| "the end".to_owned(), describe);
        Err(ExprError::at(
            self.offset(),
            format!("expected `{op}`, found {found}"),
        ))
    }

    fn nested<T>(
        &mut self,
        parse: impl FnOnce(&mut Self) -> Result<T, ExprError>,
    ) -> Result<T, ExprError> {
        if self.depth >= MAX_DEPTH {
            return Err(ExprError::at(self.offset(), "expression nested too deeply"));
        }
        self.depth += 1;
        let result = parse(self);
        self.depth -= 1;
        result
    }

    fn conditional(&mut self) -> Result<Ast, ExprError> {
        self.nested(|p| {
            let then = p.or()?;
            if !p.eat_keyword("if") {
                return Ok(then);
            }
            let condition = p.or()?;
            if !p.eat_keyword("else") {
                return Err(ExprError::at(
                    p.offset(),
                    "expected `else` in `a if condition else b`",
                ));
            }
            let otherwise = p.conditional()?;
            Ok(Ast::If {
                condition: Box::new(condition),
                then: Box::new(then),
                otherwise: Box::new(otherwise),
            })
        })
    }

    fn or(&mut self) -> Result<Ast, ExprError> {
        let first = self.and()?;
        if !self.is_keyword("or") {
            return Ok(first);
        }
        let mut operands = vec![first];
        while self.eat_keyword("or") {
            operands.push(self.and()?);
        }
        Ok(Ast::Or(operands))
    }

    fn and(&mut self) -> Result<Ast, ExprError> {
        let first = self.not()?;
        if !self.is_keyword("and") {
            return Ok(first);
        }
        let mut operands = vec![first];
        while self.eat_keyword("and") {
            operands.push(self.not()?);
        }
        Ok(Ast::And(operands))
    }

    fn not(&mut self) -> Result<Ast, ExprError> {
        if self.eat_keyword("not") {
            return self.nested(|p| Ok(Ast::Not(Box::new(p.not()?))));
        }
        self.comparison()
    }

    fn comparison_operator(&mut self) -> Option<&'static str> {
        for op in ["==", "!=", "<=", ">=", "<", ">"] {
            if self.eat_op(op) {
                return Some(op);
            }
        }
        if self.eat_keyword("in") {
            return Some("in");
        }
        if self.is_keyword("not")
            && matches!(self.tokens.get(self.at + 1), Some((Token::Name(n), _)) if n == "in")
        {
            self.at += 2;
            return Some("not in");
        }
        None
    }

    fn comparison(&mut self) -> Result<Ast, ExprError> {
        let first = self.arithmetic()?;
        let mut operands = vec![first];
        let mut operators = Vec::new();
        while let Some(op) = self.comparison_operator() {
            operators.push(op);
            operands.push(self.arithmetic()?);
        }
        if operators.is_empty() {
            return Ok(operands.pop().unwrap_or(Ast::None));
        }
        Ok(Ast::Compare(operands, operators))
    }

    fn arithmetic(&mut self) -> Result<Ast, ExprError> {
        self.chain(&["+", "-"], Self::term)
    }

    fn term(&mut self) -> Result<Ast, ExprError> {
        self.chain(&["*", "//", "/", "%"], Self::factor)
    }

    /// Operands parsed by `operand`, joined left to right by any of `operators`.
    fn chain(
        &mut self,
        operators: &[&'static str],
        operand: fn(&mut Self) -> Result<Ast, ExprError>,
    ) -> Result<Ast, ExprError> {
        let first = operand(self)?;
        let mut rest = Vec::new();
        while let Some(op) = operators.iter().find(|op| self.is_op(op)) {
            self.at += 1;
            rest.push((*op, operand(self)?));
        }
        Ok(if rest.is_empty() {
            first
        } else {
            Ast::Chain(Box::new(first), rest)
        })
    }

    fn factor(&mut self) -> Result<Ast, ExprError> {
        if self.eat_op("-") {
            return self.nested(|p| Ok(Ast::Neg(Box::new(p.factor()?))));
        }
        if self.eat_op("+") {
            return self.nested(Self::factor);
        }
        let base = self.postfix()?;
        if self.eat_op("**") {
            let exponent = self.nested(Self::factor)?;
            return Ok(Ast::Binary("**", Box::new(base), Box::new(exponent)));
        }
        Ok(base)
    }

    fn postfix(&mut self) -> Result<Ast, ExprError> {
        let mut value = self.atom()?;
        loop {
            if self.is_op("(") {
                let Ast::Name(name) = value else {
                    return Err(ExprError::at(
                        self.offset(),
                        "only named functions can be called",
                    ));
                };
                let function = functions::callable(&name).ok_or_else(|| ExprError {
                    offset: None,
                    message: format!("function `{name}` is not defined"),
                })?;
                self.at += 1;
                let args = self.sequence(")")?;
                value = Ast::Call(function, args);
            } else if self.eat_op("[") {
                value = self.nested(|p| p.subscript(value))?;
            } else {
                return Ok(value);
            }
        }
    }

    fn subscript(&mut self, target: Ast) -> Result<Ast, ExprError> {
        let start = if self.is_op(":") {
            None
        } else {
            Some(Box::new(self.conditional()?))
        };
        if !self.eat_op(":") {
            self.expect_op("]")?;
            let index = start.ok_or_else(|| ExprError::at(self.offset(), "empty index"))?;
            return Ok(Ast::Index(Box::new(target), index));
        }
        let end = if self.is_op("]") {
            None
        } else {
            Some(Box::new(self.conditional()?))
        };
        self.expect_op("]")?;
        Ok(Ast::Slice(Box::new(target), start, end))
    }

    /// Comma-separated expressions up to `close`, a trailing comma allowed.
    fn sequence(&mut self, close: &str) -> Result<Vec<Ast>, ExprError> {
        let mut items = Vec::new();
        while !self.eat_op(close) {
            items.push(self.conditional()?);
            if !self.eat_op(",") {
                self.expect_op(close)?;
                break;
            }
        }
        Ok(items)
    }

    fn atom(&mut self) -> Result<Ast, ExprError> {
        let offset = self.offset();
        let Some((token, _)) = self.tokens.get(self.at) else {
            return Err(ExprError::at(offset, "unexpected end of expression"));
        };
        self.at += 1;
        Ok(match token {
            Token::Int(n) => Ast::Int(*n),
            Token::Float(x) => Ast::Float(*x),
            Token::Str(s) => Ast::Str(s.clone()),
            Token::Name(name) => self.name(name, offset)?,
            Token::Op("(") => self.nested(|p| {
                let first_is_close = p.is_op(")");
                let mut items = p.sequence(")")?;
                let trailing_comma = p
                    .tokens
                    .get(p.at.wrapping_sub(2))
                    .is_some_and(|(t, _)| *t == Token::Op(","));
                Ok(if items.len() == 1 && !trailing_comma && !first_is_close {
                    items.remove(0)
                } else {
                    Ast::List(items)
                })
            })?,
            Token::Op("[") => self.nested(|p| Ok(Ast::List(p.sequence("]")?)))?,
            other => {
                return Err(ExprError::at(
                    offset,
                    format!("unexpected {}", describe(other)),
                ));
            }
        })
    }

    fn name(&mut self, name: &str, offset: usize) -> Result<Ast, ExprError> {
        Ok(match name {
            "True" => Ast::Bool(true),
            "False" => Ast::Bool(false),
            "None" => Ast::None,
            _ if KEYWORDS.contains(&name) => {
                return Err(ExprError::at(
                    offset,
                    format!("unexpected keyword `{name}`"),
                ));
            }
            _ if self.eat_op(".") => match self.tokens.get(self.at) {
                Some((Token::Name(attribute), _)) => {
                    self.at += 1;
                    let name = format!("{name}.{attribute}");
                    match functions::constant(&name) {
                        Some(value) => Ast::Float(value),
                        None => Ast::Name(name),
                    }
                }
                _ => return Err(ExprError::at(self.offset(), "expected a name after `.`")),
            },
            _ => Ast::Name(name.to_owned()),
        })
    }
}
