//! Syntax errors that `ron` misnames, told by what is written around them: a file that ends
//! inside an unclosed bracket (`ron`: "expected comma" past the last line), a list left
//! open before the next field, a unit variant written `Box()`, positional values where
//! named fields belong (`Obj("x.obj")`), a missing comma (reported where it belongs, after
//! the value before it) and text after the scene's closing `)`.

use ron::error::Error as RonError;

use super::located::Pos;
use super::ron_brackets::{char_offset, end_of_last_line, scan, unclosed_at_end};
use super::ron_forms::{positional_instead_of_named, takes_named_fields};

/// A better message for a `ron` error.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Hint {
    /// Where to report it.
    pub at: Pos,
    /// What is wrong.
    pub message: String,
    /// How to fix it.
    pub help: String,
}

/// A better message for `code`, which `ron` reported at `at` of `text`; `None` keeps
/// `ron`'s.
pub fn explain(text: &str, code: &RonError, at: Pos) -> Option<Hint> {
    let chars: Vec<char> = text.chars().collect();
    let offset = char_offset(text, at.line, at.column);
    if let Some(hint) = ends_inside_bracket(text, offset) {
        return Some(hint);
    }
    if let Some(hint) = positional_call(text, at) {
        return Some(hint);
    }
    if let Some(hint) = list_open_before_field(text, &chars, offset, at) {
        return Some(hint);
    }
    match code {
        RonError::ExpectedComma => {
            unit_with_parentheses(&chars, offset).or_else(|| missing_comma(text, offset))
        }
        RonError::ExpectedIdentifier => positional_fields(text, &chars, offset),
        RonError::TrailingCharacters => {
            let (close, c) = scan(text, offset).last?;
            Some(Hint {
                at,
                message: "unexpected text after the scene".into(),
                help: format!(
                    "there is text after the scene's closing `{c}` at {}:{}; a file holds \
                     exactly one `Scene(...)`: delete the text after it",
                    close.line, close.column
                ),
            })
        }
        _ => None,
    }
}

/// Nothing but blanks and comments from `offset` on, and brackets left open.
fn ends_inside_bracket(text: &str, offset: usize) -> Option<Hint> {
    let end = scan(text, usize::MAX).last_end?;
    if offset < char_offset(text, end.line, end.column) {
        return None;
    }
    let open = unclosed_at_end(text)?;
    let close = closer(open.bracket);
    Some(Hint {
        at: end_of_last_line(text),
        message: format!("the file ends inside an unclosed `{}`", open.bracket),
        help: format!(
            "the `{}` opened at {}:{} is not closed: close it with `{close}`",
            open.bracket, open.pos.line, open.pos.column
        ),
    })
}

fn closer(open: char) -> char {
    match open {
        '(' => ')',
        '[' => ']',
        _ => '}',
    }
}

/// An identifier at `offset`.
fn identifier_at(chars: &[char], offset: usize) -> String {
    chars
        .get(offset..)
        .unwrap_or_default()
        .iter()
        .take_while(|c| c.is_alphanumeric() || **c == '_')
        .collect()
}

/// `name:` where a list item belongs: the list before it is not closed.
fn list_open_before_field(text: &str, chars: &[char], offset: usize, at: Pos) -> Option<Hint> {
    let name = identifier_at(chars, offset);
    if name.is_empty() || !name.starts_with(|c: char| c.is_alphabetic() || c == '_') {
        return None;
    }
    let mut after = offset + name.chars().count();
    while chars.get(after).is_some_and(|c| c.is_whitespace()) {
        after += 1;
    }
    if chars.get(after) != Some(&':') || chars.get(after + 1) == Some(&':') {
        return None;
    }
    let list = *scan(text, offset).open.last()?;
    (list.bracket == '[').then(|| Hint {
        at,
        message: format!(
            "the list opened at {}:{} is not closed",
            list.pos.line, list.pos.column
        ),
        help: format!("add `]` before `{name}:`"),
    })
}

/// The identifier that ends just before `offset` (blanks between allowed): its start.
pub(super) fn identifier_before(chars: &[char], offset: usize) -> Option<(usize, String)> {
    let mut end = offset;
    while end > 0 && chars[end - 1].is_whitespace() {
        end -= 1;
    }
    let mut start = end;
    while start > 0 && (chars[start - 1].is_alphanumeric() || chars[start - 1] == '_') {
        start -= 1;
    }
    let name: String = chars[start..end].iter().collect();
    name.starts_with(|c: char| c.is_alphabetic() || c == '_')
        .then_some((start, name))
}

/// Line and column of character index `offset`.
fn pos_of(chars: &[char], offset: usize) -> Pos {
    let before = &chars[..offset.min(chars.len())];
    let line = 1 + before.iter().filter(|&&c| c == '\n').count();
    let column = 1 + before.iter().rev().take_while(|&&c| c != '\n').count();
    Pos { line, column }
}

/// `Box()`: `ron` read the unit variant `Box` and stopped at the `(`.
fn unit_with_parentheses(chars: &[char], offset: usize) -> Option<Hint> {
    if chars.get(offset) != Some(&'(') {
        return None;
    }
    let (start, name) = identifier_before(chars, offset)?;
    Some(Hint {
        at: pos_of(chars, start),
        message: format!("{name} takes no value: write it bare as {name}"),
        help: format!("delete the `(…)` after {name}"),
    })
}

/// `Name(value, …)` where named fields belong: `ron` expected a field name at the value.
fn positional_fields(text: &str, chars: &[char], offset: usize) -> Option<Hint> {
    let (paren, c) = scan(text, offset).last?;
    if c != '(' {
        return None;
    }
    let paren = char_offset(text, paren.line, paren.column);
    let (start, name) = identifier_before(chars, paren)?;
    let first: String = if chars.get(offset) == Some(&'"') {
        let len = chars[offset + 1..]
            .iter()
            .position(|&c| c == '"' || c == '\n')
            .map_or(0, |n| n + 2);
        chars[offset..(offset + len).min(chars.len())]
            .iter()
            .collect()
    } else {
        String::new()
    };
    let (message, help) = positional_instead_of_named(&name, &first);
    Some(Hint {
        at: pos_of(chars, start),
        message,
        help,
    })
}

/// Any error inside the parentheses of a node (or file variant) that takes named fields,
/// when a value up to the error is written without its name (`Mix(Uv, 1)`: `ron` said
/// `unknown field "Uv" in Mix`; `Checker(8)`: `found invalid std identifier "8"`): the
/// call in the wrong style, reported at the node's name with its form.
pub fn positional_call(text: &str, at: Pos) -> Option<Hint> {
    let chars: Vec<char> = text.chars().collect();
    let offset = char_offset(text, at.line, at.column);
    let call = *scan(text, offset).open.last()?;
    if call.bracket != '(' {
        return None;
    }
    let paren = char_offset(text, call.pos.line, call.pos.column);
    let (start, name) = identifier_before(&chars, paren)?;
    if !takes_named_fields(&name) {
        return None;
    }
    let values = top_level_values(&chars, paren + 1, offset);
    let unnamed = values.iter().any(|&v| !named_value_at(&chars, v));
    if !unnamed {
        return None;
    }
    let first: String = values
        .first()
        .filter(|&&v| chars[v] == '"')
        .map(|&v| {
            let len = chars[v + 1..]
                .iter()
                .position(|&c| c == '"' || c == '\n')
                .map_or(1, |n| n + 2);
            chars[v..(v + len).min(chars.len())].iter().collect()
        })
        .unwrap_or_default();
    let (message, help) = positional_instead_of_named(&name, &first);
    Some(Hint {
        at: pos_of(&chars, start),
        message,
        help,
    })
}

/// Where each value (or `name: value` field) between `from` and `upto` starts, at the
/// top level of the parentheses that open just before `from` (strings skipped); a value
/// that starts at `upto` counts.
fn top_level_values(chars: &[char], from: usize, upto: usize) -> Vec<usize> {
    let mut starts = Vec::new();
    let mut depth = 0usize;
    let mut expect_value = true;
    let mut i = from;
    while i < chars.len() && i <= upto {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        if depth == 0 && expect_value && c != ',' && !matches!(c, ')' | ']' | '}') {
            starts.push(i);
            expect_value = false;
        }
        match c {
            '"' => {
                i += 1;
                while i < chars.len() && chars[i] != '"' {
                    i += if chars[i] == '\\' { 2 } else { 1 };
                }
            }
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' if depth == 0 => break,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => expect_value = true,
            _ => {}
        }
        i += 1;
    }
    starts
}

/// Whether the value at `at` is written `name: …`.
fn named_value_at(chars: &[char], at: usize) -> bool {
    let name = identifier_at(chars, at);
    if !name.starts_with(|c: char| c.is_alphabetic() || c == '_') {
        return false;
    }
    let mut after = at + name.chars().count();
    while chars.get(after).is_some_and(|c| c.is_whitespace()) {
        after += 1;
    }
    chars.get(after) == Some(&':') && chars.get(after + 1) != Some(&':')
}

/// A missing comma, reported just after the value it should follow.
fn missing_comma(text: &str, offset: usize) -> Option<Hint> {
    let before = scan(text, offset);
    let (_, last) = before.last?;
    if matches!(last, '(' | '[' | '{' | ',' | ':') {
        return None;
    }
    Some(Hint {
        at: before.last_end?,
        message: "expected comma".into(),
        help: "add ',' here".into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hint(
        text: &str,
        code: RonError,
        line: usize,
        column: usize,
    ) -> Option<(Pos, String, String)> {
        explain(text, &code, Pos { line, column }).map(|h| (h.at, h.message, h.help))
    }

    fn pos(line: usize, column: usize) -> Pos {
        Pos { line, column }
    }

    #[test]
    fn names_what_ron_calls_a_missing_comma() {
        let unclosed = "Scene(\n    render: (root: \"w\",\n)\n";
        assert_eq!(
            hint(unclosed, RonError::ExpectedComma, 4, 1),
            Some((
                pos(3, 2),
                "the file ends inside an unclosed `(`".into(),
                "the `(` opened at 2:13 is not closed: close it with `)`".into()
            ))
        );
        let unit = "(filter: Box ())";
        assert_eq!(
            hint(unit, RonError::ExpectedComma, 1, 14),
            Some((
                pos(1, 10),
                "Box takes no value: write it bare as Box".into(),
                "delete the `(…)` after Box".into()
            ))
        );
        let comma = "(a: [1] // one\n b: 2)";
        assert_eq!(
            hint(comma, RonError::ExpectedComma, 2, 2),
            Some((pos(1, 8), "expected comma".into(), "add ',' here".into()))
        );
    }

    #[test]
    fn a_field_where_a_list_item_belongs_closes_the_list() {
        let text = "(groups: [(name: \"w\"),\n render: (),\n)";
        let (at, message, help) = hint(text, RonError::ExpectedIdentifier, 2, 2).unwrap();
        assert_eq!(at, pos(2, 2));
        assert_eq!(message, "the list opened at 1:10 is not closed");
        assert_eq!(help, "add `]` before `render:`");
    }

    #[test]
    fn positional_values_where_fields_are_named() {
        let text = "(mesh: Obj(\"x.obj\"), t: Mix(1, 2, 0.5))";
        assert_eq!(
            hint(text, RonError::ExpectedIdentifier, 1, 12).map(|h| (h.0, h.1)),
            Some((
                pos(1, 8),
                "Obj takes named fields: Obj(file: \"x.obj\")".into()
            ))
        );
        assert_eq!(
            hint(text, RonError::ExpectedIdentifier, 1, 29).map(|h| h.1),
            Some("Mix takes named inputs: Mix(a: …, b: …, t: …)".into())
        );
        assert_eq!(
            hint("(a: 1);", RonError::TrailingCharacters, 1, 7).map(|h| h.2),
            Some(
                "there is text after the scene's closing `)` at 1:6; a file holds exactly \
                 one `Scene(...)`: delete the text after it"
                    .into()
            )
        );
    }
}
