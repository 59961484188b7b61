//! Tokens of the Python expression subset used in templates.

use super::ExprError;

#[derive(Debug, Clone, PartialEq)]
pub(super) enum Token {
    Int(i64),
    Float(f64),
    Str(String),
    Name(String),
    /// Operators and punctuation: `+ - * / // % ** == != < <= > >= ( ) [ ] , : .`
    Op(&'static str),
}

/// A token and the character offset where it starts in the expression.
pub(super) type Spanned = (Token, usize);

const OPERATORS: [&str; 19] = [
    "**", "//", "==", "!=", "<=", ">=", "+", "-", "*", "/", "%", "<", ">", "(", ")", "[", "]", ",",
    ":",
];

pub(super) fn tokenize(source: &str) -> Result<Vec<Spanned>, ExprError> {
    let chars: Vec<char> = source.chars().collect();
    let mut tokens = Vec::new();
    let mut at = 0;
    while at < chars.len() {
        let c = chars[at];
        if c.is_whitespace() {
            at += 1;
        } else if c.is_ascii_digit()
            || (c == '.' && chars.get(at + 1).is_some_and(char::is_ascii_digit))
        {
            let (token, end) = number(&chars, at)?;
            tokens.push((token, at));
            at = end;
        } else if c == '\'' || c == '"' {
            let (text, end) = string(&chars, at)?;
            tokens.push((Token::Str(text), at));
            at = end;
        } else if c.is_alphabetic() || c == '_' {
            let end = scan(&chars, at, |c| c.is_alphanumeric() || c == '_');
            tokens.push((Token::Name(chars[at..end].iter().collect()), at));
            at = end;
        } else if c == '.' {
            tokens.push((Token::Op("."), at));
            at += 1;
        } else {
            let rest: String = chars[at..chars.len().min(at + 2)].iter().collect();
            let op = OPERATORS
                .iter()
                .find(|op| rest.starts_with(**op))
                .ok_or_else(|| ExprError::at(at, format!("unexpected character {c:?}")))?;
            tokens.push((Token::Op(op), at));
            at += op.chars().count();
        }
    }
    Ok(tokens)
}

fn scan(chars: &[char], from: usize, accept: impl Fn(char) -> bool) -> usize {
    chars[from..]
        .iter()
        .position(|&c| !accept(c))
        .map_or(chars.len(), |n| from + n)
}

fn number(chars: &[char], start: usize) -> Result<(Token, usize), ExprError> {
    let mut end = scan(chars, start, |c| c.is_ascii_digit() || c == '_');
    let mut float = false;
    if chars.get(end) == Some(&'.') {
        float = true;
        end = scan(chars, end + 1, |c| c.is_ascii_digit() || c == '_');
    }
    if matches!(chars.get(end), Some('e' | 'E')) {
        let mut exponent = end + 1;
        if matches!(chars.get(exponent), Some('+' | '-')) {
            exponent += 1;
        }
        if chars.get(exponent).is_some_and(char::is_ascii_digit) {
            float = true;
            end = scan(chars, exponent, |c| c.is_ascii_digit());
        }
    }
    let text: String = chars[start..end].iter().filter(|&&c| c != '_').collect();
    let token = if float {
        text.parse().map(Token::Float).ok()
    } else {
        text.parse().map(Token::Int).ok()
    };
    token
        .map(|token| (token, end))
        .ok_or_else(|| ExprError::at(start, format!("invalid number {text:?}")))
}

fn string(chars: &[char], start: usize) -> Result<(String, usize), ExprError> {
    let quote = chars[start];
    let mut text = String::new();
    let mut at = start + 1;
    while let Some(&c) = chars.get(at) {
        match c {
            c if c == quote => return Ok((text, at + 1)),
            '\\' => {
                let escaped = chars
                    .get(at + 1)
                    .ok_or_else(|| ExprError::at(at, "unterminated string"))?;
                text.push(match escaped {
                    'n' => '\n',
                    't' => '\t',
                    other => *other,
                });
                at += 2;
            }
            c => {
                text.push(c);
                at += 1;
            }
        }
    }
    Err(ExprError::at(start, "unterminated string"))
}
