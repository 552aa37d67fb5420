//! A bracket left open in the middle of a file: the next field (`bind:` after
//! `Lambert(albedo: (1, 1, 1),`), the next list element (`(name: "n", …)`) or a closer of
//! another kind (`]` where a `(` is open) comes while the `(` is still open, and `ron`
//! misnames it (`unknown field "bind" in Lambert`, `expected identifier`, `expected
//! comma`). The bracket is found by closing it where the suggestion says and reading the
//! file again: when `ron` then gets past the place of its first error, the bracket is the
//! one to close; otherwise `ron`'s own message stands (a misspelt field stays a misspelt
//! field).

use super::located::Pos;
use super::ron_brackets::{char_offset, scan, Open};
use super::ron_hints::Hint;

/// At most this many brackets are closed in one suggestion (`)]` closes a list element
/// and its list).
const MOST_CLOSED: usize = 3;

/// A message for the error `ron` reported at `at` of `text` when it comes from an unclosed
/// bracket; `first_error` reads a text and gives the position of its first error (`None`
/// when it reads).
pub fn explain(text: &str, at: Pos, first_error: impl Fn(&str) -> Option<Pos>) -> Option<Hint> {
    let chars: Vec<char> = text.chars().collect();
    let offset = char_offset(text, at.line, at.column);
    let before = scan(text, offset);
    let innermost = *before.open.last()?;
    let here = *chars.get(offset)?;
    let (insert, next) = if matches!(here, ')' | ']' | '}') {
        if here == closer(innermost.bracket) {
            return None;
        }
        (offset, format!("`{here}`"))
    } else {
        let (comma, ',') = before.last? else {
            return None;
        };
        let field = field_name_at(&chars, offset);
        if innermost.bracket != '(' || (here != '(' && field.is_none()) {
            return None;
        }
        let next = field.map_or("`(`".to_string(), |name| format!("`{name}:`"));
        (char_offset(text, comma.line, comma.column), next)
    };
    let insert_at = pos_of(&chars, insert);
    for k in 1..=MOST_CLOSED.min(before.open.len()) {
        let closing: Vec<Open> = before.open.iter().rev().take(k).copied().collect();
        let closers: String = closing.iter().map(|o| closer(o.bracket)).collect();
        let repaired: String = chars[..insert]
            .iter()
            .chain(closers.chars().collect::<Vec<_>>().iter())
            .chain(chars[insert..].iter())
            .collect();
        let gets_past = first_error(&repaired)
            .is_none_or(|e| char_offset(&repaired, e.line, e.column) > offset + k);
        if gets_past {
            return Some(hint(&chars, at, &closing, &closers, insert_at, &next));
        }
    }
    None
}

/// The message for `closing` (innermost first) closed with `closers` at `insert_at`.
fn hint(
    chars: &[char],
    at: Pos,
    closing: &[Open],
    closers: &str,
    insert_at: Pos,
    next: &str,
) -> Hint {
    let describe = |o: &Open| {
        let of = (o.bracket == '(')
            .then(|| name_before(chars, o.pos))
            .flatten()
            .map(|name| format!(" of {name}"))
            .unwrap_or_default();
        format!(
            "the `{}`{of} opened at {}:{}",
            o.bracket, o.pos.line, o.pos.column
        )
    };
    let named: Vec<String> = closing.iter().map(describe).collect();
    let message = match named.as_slice() {
        [one] => format!("{one} is not closed"),
        [inner @ .., outer] => format!("{} and {outer} are not closed", inner.join(", ")),
        [] => String::new(),
    };
    let them = if closing.len() == 1 { "it" } else { "them" };
    Hint {
        at,
        message,
        help: format!(
            "close {them} with `{closers}` at {}:{}, before {next}",
            insert_at.line, insert_at.column
        ),
    }
}

fn closer(open: char) -> char {
    match open {
        '(' => ')',
        '[' => ']',
        _ => '}',
    }
}

/// `name` of `name:` at `offset` (not `name::`).
fn field_name_at(chars: &[char], offset: usize) -> Option<String> {
    let name: String = chars[offset..]
        .iter()
        .take_while(|c| c.is_alphanumeric() || **c == '_')
        .collect();
    if !name.starts_with(|c: char| c.is_alphabetic() || c == '_') {
        return None;
    }
    let mut after = offset + name.chars().count();
    while chars.get(after).is_some_and(|c| c.is_whitespace()) {
        after += 1;
    }
    (chars.get(after) == Some(&':') && chars.get(after + 1) != Some(&':')).then_some(name)
}

/// The name written just before the `(` at `pos`, if any: `Lambert` of `Lambert(`,
/// `` `options:` `` of `options: (`.
fn name_before(chars: &[char], pos: Pos) -> Option<String> {
    let text: String = chars.iter().collect();
    let mut end = char_offset(&text, pos.line, pos.column);
    while end > 0 && chars[end - 1].is_whitespace() {
        end -= 1;
    }
    if end > 0 && chars[end - 1] == ':' {
        let field = name_before(chars, pos_of(chars, end - 1))?;
        return Some(format!("`{field}:`"));
    }
    let mut start = end;
    while start > 0 && (chars[start - 1].is_alphanumeric() || chars[start - 1] == '_') {
        start -= 1;
    }
    let name: String = chars[start..end].iter().collect();
    name.starts_with(|c: char| c.is_alphabetic())
        .then_some(name)
}

/// Line and column of character index `offset`.
fn pos_of(chars: &[char], offset: usize) -> Pos {
    let before = &chars[..offset.min(chars.len())];
    let line = 1 + before.iter().filter(|&&c| c == '\n').count();
    let column = 1 + before.iter().rev().take_while(|&&c| c != '\n').count();
    Pos { line, column }
}
