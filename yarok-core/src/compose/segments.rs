//! `{expression}` segments in attribute text.

/// A piece of attribute text: literal, or the source of an expression.
pub(super) enum Segment<'a> {
    Text(&'a str),
    Expression(&'a str),
}

/// The source of an attribute that is exactly one `{expr}` (or `${expr}`).
pub(super) fn whole_expression(value: &str) -> Option<&str> {
    match segments(value).ok()?.as_slice() {
        [Segment::Expression(source)] => Some(source),
        _ => None,
    }
}

/// Splits `a {x} b ${y}` into text and expressions; `{{` and `}}` are literal braces.
pub(super) fn segments(value: &str) -> Result<Vec<Segment<'_>>, String> {
    let bytes = value.as_bytes();
    let mut out = Vec::new();
    let (mut text_start, mut at) = (0, 0);
    while at < bytes.len() {
        match bytes[at] {
            b'{' | b'}' if bytes.get(at + 1) == Some(&bytes[at]) => {
                out.push(Segment::Text(&value[text_start..=at]));
                at += 2;
                text_start = at;
            }
            b'{' => {
                let dollar = at > text_start && bytes[at - 1] == b'$';
                out.push(Segment::Text(&value[text_start..at - usize::from(dollar)]));
                let end = closing_brace(bytes, at)
                    .ok_or_else(|| format!("unclosed `{{` at character {}", at + 1))?;
                out.push(Segment::Expression(&value[at + 1..end]));
                at = end + 1;
                text_start = at;
            }
            b'}' => return Err(format!("`}}` without `{{` at character {}", at + 1)),
            _ => at += 1,
        }
    }
    out.push(Segment::Text(&value[text_start..]));
    out.retain(|s| !matches!(s, Segment::Text("")));
    Ok(out)
}

/// The `}` closing the `{` at `open`, skipping quoted strings and nested braces.
fn closing_brace(bytes: &[u8], open: usize) -> Option<usize> {
    let (mut depth, mut quote, mut at) = (0usize, None, open + 1);
    while at < bytes.len() {
        let byte = bytes[at];
        match quote {
            Some(_) if byte == b'\\' => at += 1,
            Some(q) if byte == q => quote = None,
            Some(_) => {}
            None => match byte {
                b'\'' | b'"' => quote = Some(byte),
                b'{' => depth += 1,
                b'}' if depth == 0 => return Some(at),
                b'}' => depth -= 1,
                _ => {}
            },
        }
        at += 1;
    }
    None
}
