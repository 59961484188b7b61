//! A small XML element tree that remembers where each element and attribute came from, so that
//! errors can name the template's line and column.

use std::cell::Cell;
use std::fmt;

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// Templates nested deeper than this are refused, so that no input can exhaust the stack.
const MAX_DEPTH: usize = 256;

/// A line and column in a template, both counted from 1 (columns in characters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Position {
    /// Line, from 1.
    pub line: u32,
    /// Column in characters, from 1.
    pub column: u32,
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// An attribute and where it was written.
#[derive(Debug, Clone, PartialEq)]
pub struct Attribute {
    /// Attribute name.
    pub name: String,
    /// Attribute value, unescaped.
    pub value: String,
    /// Where the attribute's name starts.
    pub position: Position,
}

/// An element: name, attributes in document order, child elements, and its position.
///
/// Text and comments are not kept: MJCF carries everything in attributes (text found between
/// elements is reported in [`Document::stray_text`]).
#[derive(Debug, PartialEq)]
pub struct Element {
    /// Tag name.
    pub name: String,
    /// Attributes in document order.
    pub attributes: Vec<Attribute>,
    /// Child elements in document order.
    pub children: Vec<Element>,
    /// Where the element's `<` is.
    pub position: Position,
    /// Which template the element was written in (an index the composer assigns).
    pub(crate) origin: usize,
    /// Which component instance owns the element's names (an index the composer assigns).
    pub(crate) owner: usize,
}

/// A template could not be parsed as XML.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct XmlError {
    /// Where the problem is.
    pub position: Position,
    /// What the problem is.
    pub message: String,
}

/// A parsed template: its root element, and the text it held between elements, which MJCF has
/// no place for and which MuJoCo's own reader ignores (a stray `]` or `>` in a published file).
#[derive(Debug)]
pub struct Document {
    /// The root element.
    pub root: Element,
    /// The text outside any element's attributes that was ignored, in document order.
    pub stray_text: Vec<StrayText>,
}

/// Text a template holds between elements, ignored as MuJoCo ignores it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StrayText {
    /// Where the text starts.
    pub position: Position,
    /// The text, without its surrounding white space.
    pub text: String,
}

impl fmt::Display for StrayText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: the text {:?} outside any element's attributes is ignored, as MuJoCo ignores it",
            self.position, self.text
        )
    }
}

impl Clone for Element {
    fn clone(&self) -> Self {
        let mut copy = self.without_children();
        if !self.children.is_empty() {
            copy.children = crate::stack::deep(|| self.children.clone());
        }
        copy
    }
}

impl Element {
    /// A new element with no attributes or children.
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            attributes: Vec::new(),
            children: Vec::new(),
            position: Position::default(),
            origin: 0,
            owner: 0,
        }
    }

    /// An element with this one's tag and place (template, owner, position) but no attributes
    /// or children, for the composer's merged sections, so that errors about them name a place.
    pub(crate) fn empty_like(&self) -> Self {
        Self {
            attributes: Vec::new(),
            ..self.without_children()
        }
    }

    /// A copy of this element without its children.
    pub fn without_children(&self) -> Self {
        Self {
            name: self.name.clone(),
            attributes: self.attributes.clone(),
            children: Vec::new(),
            position: self.position,
            origin: self.origin,
            owner: self.owner,
        }
    }

    /// The value of an attribute.
    pub fn attribute(&self, name: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|a| a.name == name)
            .map(|a| a.value.as_str())
    }

    /// The attribute record itself.
    pub fn attribute_entry(&self, name: &str) -> Option<&Attribute> {
        self.attributes.iter().find(|a| a.name == name)
    }

    /// Sets an attribute, keeping its place when it exists.
    pub fn set_attribute(&mut self, name: &str, value: impl Into<String>) {
        let value = value.into();
        match self.attributes.iter_mut().find(|a| a.name == name) {
            Some(attribute) => attribute.value = value,
            None => self.attributes.push(Attribute {
                name: name.to_owned(),
                value,
                position: self.position,
            }),
        }
    }

    /// Removes an attribute and returns it.
    pub fn take_attribute(&mut self, name: &str) -> Option<Attribute> {
        let index = self.attributes.iter().position(|a| a.name == name)?;
        Some(self.attributes.remove(index))
    }

    /// The first child with this tag.
    pub fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }

    /// Every element of this subtree, this one first, depth first.
    pub fn descendants(&self) -> Vec<&Element> {
        let mut all = vec![self];
        let mut at = 0;
        while at < all.len() {
            let element = all[at];
            all.splice(at + 1..at + 1, element.children.iter());
            at += 1;
        }
        all
    }

    /// Parses one document: its root element, and the text between elements it ignored.
    ///
    /// # Errors
    ///
    /// [`XmlError`] with the line and column of malformed XML or of a second root element.
    pub fn parse(source: &str) -> Result<Document, XmlError> {
        // The XML reader skips a byte-order mark without counting it in its offsets.
        let source = source.strip_prefix('\u{feff}').unwrap_or(source);
        let lines = LineIndex::new(source);
        let mut reader = Reader::from_str(source);
        reader.config_mut().check_end_names = true;
        let mut stack: Vec<Element> = Vec::new();
        let mut root = None;
        let mut stray_text = Vec::new();
        loop {
            let offset = reader.buffer_position() as usize;
            let event = reader.read_event().map_err(|e| XmlError {
                position: lines.position(reader.error_position() as usize),
                message: e.to_string(),
            })?;
            match event {
                Event::Start(_) | Event::Empty(_) if root.is_some() && stack.is_empty() => {
                    return Err(XmlError {
                        position: lines.position(offset),
                        message: "a template has one root element".into(),
                    });
                }
                Event::Start(_) if stack.len() >= MAX_DEPTH => {
                    return Err(XmlError {
                        position: lines.position(offset),
                        message: format!("elements nested deeper than {MAX_DEPTH}"),
                    });
                }
                Event::Start(start) => stack.push(element(&start, offset, source, &lines)?),
                Event::Empty(start) => {
                    let element = element(&start, offset, source, &lines)?;
                    attach(&mut stack, &mut root, element);
                }
                Event::End(_) => {
                    let element = stack.pop().ok_or_else(|| XmlError {
                        position: lines.position(offset),
                        message: "closing tag without an opening one".into(),
                    })?;
                    attach(&mut stack, &mut root, element);
                }
                Event::Text(text) if !text.iter().all(u8::is_ascii_whitespace) => {
                    let leading = text.iter().take_while(|b| b.is_ascii_whitespace()).count();
                    stray_text.push(StrayText {
                        position: lines.position(offset + leading),
                        text: String::from_utf8_lossy(&text).trim().to_owned(),
                    });
                }
                Event::Eof => break,
                _ => {}
            }
        }
        if let Some(open) = stack.last() {
            return Err(XmlError {
                position: open.position,
                message: format!("<{}> is never closed", open.name),
            });
        }
        let root = root.ok_or_else(|| XmlError {
            position: Position { line: 1, column: 1 },
            message: "the template is empty".into(),
        })?;
        Ok(Document { root, stray_text })
    }

    /// Writes the tree as indented XML.
    pub fn to_xml(&self) -> String {
        let mut out = String::with_capacity(4096);
        self.write(&mut out, 0);
        out
    }

    fn write(&self, out: &mut String, depth: usize) {
        for _ in 0..depth {
            out.push_str("  ");
        }
        out.push('<');
        out.push_str(&self.name);
        for attribute in &self.attributes {
            out.push(' ');
            out.push_str(&attribute.name);
            out.push_str("=\"");
            escape(&attribute.value, out);
            out.push('"');
        }
        if self.children.is_empty() {
            out.push_str("/>\n");
            return;
        }
        out.push_str(">\n");
        crate::stack::deep(|| {
            for child in &self.children {
                child.write(out, depth + 1);
            }
        });
        for _ in 0..depth {
            out.push_str("  ");
        }
        out.push_str("</");
        out.push_str(&self.name);
        out.push_str(">\n");
    }
}

fn attach(stack: &mut [Element], root: &mut Option<Element>, element: Element) {
    match stack.last_mut() {
        Some(parent) => parent.children.push(element),
        None => *root = Some(element),
    }
}

fn escape(value: &str, out: &mut String) {
    for c in value.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\n' => out.push_str("&#10;"),
            c => out.push(c),
        }
    }
}

fn element(
    start: &BytesStart<'_>,
    offset: usize,
    source: &str,
    lines: &LineIndex,
) -> Result<Element, XmlError> {
    let name = String::from_utf8_lossy(start.name().as_ref()).into_owned();
    let raw = source.get(offset..).ok_or_else(|| XmlError {
        position: lines.position(offset),
        message: "the XML reader lost its place in the text".into(),
    })?;
    let mut cursor = 1 + name.len();
    let mut attributes = Vec::new();
    for attribute in start.attributes() {
        let attribute = attribute.map_err(|e| XmlError {
            position: lines.position(offset),
            message: e.to_string(),
        })?;
        let key = String::from_utf8_lossy(attribute.key.as_ref()).into_owned();
        let at = attribute_offset(raw, cursor, &key);
        cursor = at + key.len();
        cursor = skip_value(raw, cursor);
        let value = attribute
            .unescape_value()
            .map_err(|e| XmlError {
                position: lines.position(offset + at),
                message: e.to_string(),
            })?
            .into_owned();
        attributes.push(Attribute {
            name: key,
            value,
            position: lines.position(offset + at),
        });
    }
    Ok(Element {
        name,
        attributes,
        children: Vec::new(),
        position: lines.position(offset),
        origin: 0,
        owner: 0,
    })
}

/// Where `key=` starts in the raw tag, searching from `cursor`.
fn attribute_offset(raw: &str, cursor: usize, key: &str) -> usize {
    raw.get(cursor..)
        .and_then(|rest| rest.find(key))
        .map_or(cursor, |found| cursor + found)
}

/// Moves past `= "value"`.
fn skip_value(raw: &str, cursor: usize) -> usize {
    let bytes = raw.as_bytes();
    let Some(open) = (cursor..bytes.len()).find(|&i| bytes[i] == b'"' || bytes[i] == b'\'') else {
        return cursor;
    };
    (open + 1..bytes.len())
        .find(|&i| bytes[i] == bytes[open])
        .map_or(cursor, |close| close + 1)
}

/// Byte offsets of line starts, to turn offsets into line:column.
struct LineIndex<'a> {
    source: &'a str,
    starts: Vec<usize>,
    /// The last offset asked for, its line and its column (characters from the line's start):
    /// a parse asks in increasing order, so a long line's columns are counted once, not once
    /// per attribute.
    last: Cell<(usize, usize, usize)>,
}

impl<'a> LineIndex<'a> {
    fn new(source: &'a str) -> Self {
        let starts = std::iter::once(0)
            .chain(source.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        Self {
            source,
            starts,
            last: Cell::new((0, 1, 0)),
        }
    }

    fn position(&self, offset: usize) -> Position {
        let offset = offset.min(self.source.len());
        let line = self.starts.partition_point(|&start| start <= offset);
        let start = self.starts[line - 1];
        let (last_offset, last_line, last_column) = self.last.get();
        let (from, counted) = if last_line == line && (start..=offset).contains(&last_offset) {
            (last_offset, last_column)
        } else {
            (start, 0)
        };
        let column = counted
            + self
                .source
                .get(from..offset)
                .map_or(offset - from, |s| s.chars().count());
        self.last.set((offset, line, column));
        Position {
            line: line as u32,
            column: column as u32 + 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_byte_order_mark_is_skipped() {
        let element = Element::parse("\u{feff}\u{c}<mujoco>\n <¡/></mujoco>")
            .unwrap()
            .root;
        assert_eq!(element.children[0].name, "¡");
        assert_eq!(
            element.children[0].position,
            Position { line: 2, column: 2 }
        );
    }

    #[test]
    fn parses_with_positions_and_writes_back() {
        let source = "<mujoco>\n  <!-- c -->\n  <worldbody>\n    <geom name=\"a\" size=\"{x &amp; y}\"/>\n  </worldbody>\n</mujoco>";
        let root = Element::parse(source).unwrap().root;
        let geom = &root.children[0].children[0];
        assert_eq!(geom.position, Position { line: 4, column: 5 });
        assert_eq!(
            geom.attribute_entry("size").unwrap().position,
            Position {
                line: 4,
                column: 20
            }
        );
        assert_eq!(geom.attribute("size"), Some("{x & y}"));
        let reparsed = Element::parse(&root.to_xml()).unwrap().root;
        let geom_again = &reparsed.children[0].children[0];
        assert_eq!(geom_again.attribute("size"), Some("{x & y}"));
        assert_eq!(geom_again.attribute("name"), Some("a"));
    }

    #[test]
    fn malformed_xml_names_the_place() {
        let error = Element::parse("<mujoco>\n  <body>\n</mujoco>").unwrap_err();
        assert_eq!(error.position.line, 3, "{error:?}");
        let error = Element::parse("<a/><b/>").unwrap_err();
        assert_eq!(error.message, "a template has one root element");
        assert!(Element::parse("").is_err());
    }

    #[test]
    fn stray_text_is_ignored_and_reported_where_it_is() {
        let parsed = Element::parse("<mujoco>\n  <visual/>>\n  <a>  ]\n</a></mujoco>").unwrap();
        assert_eq!(parsed.root.children.len(), 2);
        let found: Vec<String> = parsed.stray_text.iter().map(|s| s.to_string()).collect();
        assert_eq!(
            found,
            [
                "2:12: the text \">\" outside any element's attributes is ignored, as MuJoCo ignores it",
                "3:8: the text \"]\" outside any element's attributes is ignored, as MuJoCo ignores it",
            ]
        );
    }
}
