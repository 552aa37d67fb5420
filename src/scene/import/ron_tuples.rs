//! A tuple written with more values than it takes (`albedo: (0.5, 0.5, 0.5, 1)`): `ron`
//! stops at the first extra value with "expected closing `)`", where a tuple with too few
//! values gets "expected a tuple of size 3 but found 2 elements". The extra value is
//! reported in that same style, with the count of values written.

use ron::error::Error as RonError;

use super::located::Pos;
use super::ron_brackets::{char_offset, scan};
use super::ron_hints::Hint;

/// Fields whose three values are a linear RGB colour (a colour with alpha, such as a
/// contour's `color`, takes four values and is never told it is RGB).
const COLOUR_FIELDS: &[&str] = &[
    "albedo",
    "ambient",
    "background",
    "base_color",
    "color",
    "contrast",
    "diffuse",
    "emission",
    "glossy",
    "inside",
    "opacity",
    "outside",
    "reflection",
    "refraction",
    "sigma_a",
    "sigma_s",
    "specular",
];

/// A message for `ron`'s "expected closing `)`" at `at` of `text` when `at` is an extra
/// value of an unnamed tuple; `None` keeps `ron`'s.
pub fn extra_values(text: &str, code: &RonError, at: Pos) -> Option<Hint> {
    if !matches!(code, RonError::ExpectedStructLikeEnd) {
        return None;
    }
    let chars: Vec<char> = text.chars().collect();
    let offset = char_offset(text, at.line, at.column);
    let before = scan(text, offset);
    let (_, ',') = before.last? else {
        return None;
    };
    let open = *before.open.last()?;
    if open.bracket != '(' {
        return None;
    }
    let paren = char_offset(text, open.pos.line, open.pos.column);
    let field = field_before(&chars, paren);
    if field.is_none() && named_call(&chars, paren) {
        return None;
    }
    let takes = values(&chars, paren + 1, offset)?;
    let found = values(&chars, paren + 1, chars.len())?;
    if takes == 0 || found <= takes {
        return None;
    }
    let extra = match found - takes {
        1 => "the extra value".to_string(),
        n => format!("the {n} extra values"),
    };
    let rgb = takes == 3 && field.is_some_and(|f| COLOUR_FIELDS.contains(&f.as_str()));
    let help = if rgb {
        format!("remove {extra}: colours are RGB, write exactly 3 values in `(…)` (no alpha)")
    } else {
        format!("remove {extra}: write exactly {takes} values in `(…)`")
    };
    Some(Hint {
        at,
        message: format!("expected a tuple of size {takes} but found {found} elements"),
        help,
    })
}

/// The values of the parentheses whose inside starts at `from`, up to `upto` or their
/// closer; `None` when a value is written `name: …` (a struct, not a tuple).
fn values(chars: &[char], from: usize, upto: usize) -> Option<usize> {
    let mut count = 0;
    let mut depth = 0usize;
    let mut expect_value = true;
    let mut i = from;
    while i < upto.min(chars.len()) {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
            continue;
        }
        if c == '/' && next == Some('*') {
            let mut nest = 0usize;
            while i < chars.len() {
                match (chars[i], chars.get(i + 1)) {
                    ('/', Some('*')) => (nest, i) = (nest + 1, i + 2),
                    ('*', Some('/')) => {
                        (nest, i) = (nest - 1, i + 2);
                        if nest == 0 {
                            break;
                        }
                    }
                    _ => i += 1,
                }
            }
            continue;
        }
        if depth == 0 && expect_value && !matches!(c, ',' | ')' | ']' | '}') {
            count += 1;
            expect_value = false;
        }
        match c {
            '"' => {
                i += 1;
                while i < chars.len() && chars[i] != '"' {
                    i += if chars[i] == '\\' { 2 } else { 1 };
                }
            }
            ':' if depth == 0 => return None,
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' if depth == 0 => break,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => expect_value = true,
            _ => {}
        }
        i += 1;
    }
    Some(count)
}

/// The field name of `name: (` whose `(` is at `paren`.
fn field_before(chars: &[char], paren: usize) -> Option<String> {
    let mut end = paren;
    while end > 0 && chars[end - 1].is_whitespace() {
        end -= 1;
    }
    if end < 2 || chars[end - 1] != ':' || chars[end - 2] == ':' {
        return None;
    }
    end -= 1;
    super::ron_hints::identifier_before(chars, end).map(|(_, name)| name)
}

/// Whether a name is written just before the `(` at `paren` (`Add(`: a call, whose
/// values `ron` names itself).
fn named_call(chars: &[char], paren: usize) -> bool {
    paren > 0 && (chars[paren - 1].is_alphanumeric() || chars[paren - 1] == '_')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hint(text: &str, column: usize) -> Option<(Pos, String, String)> {
        let at = Pos { line: 1, column };
        extra_values(text, &RonError::ExpectedStructLikeEnd, at).map(|h| (h.at, h.message, h.help))
    }

    #[test]
    fn extra_values_are_counted_and_colours_named() {
        let (at, message, help) = hint("(albedo: (0.5, 0.5, 0.5, 1))", 26).unwrap();
        assert_eq!(
            at,
            Pos {
                line: 1,
                column: 26
            }
        );
        assert_eq!(message, "expected a tuple of size 3 but found 4 elements");
        assert_eq!(
            help,
            "remove the extra value: colours are RGB, write exactly 3 values in `(…)` (no alpha)"
        );
        let (_, message, help) = hint("(p: (1, /* , */ 2, 3, \"a,\"))", 20).unwrap();
        assert_eq!(message, "expected a tuple of size 2 but found 4 elements");
        assert_eq!(
            help,
            "remove the 2 extra values: write exactly 2 values in `(…)`"
        );
        // A struct or a call keeps `ron`'s message.
        assert_eq!(hint("(p: (a: 1, b: 2))", 12), None);
        assert_eq!(hint("(p: Add(1, 2, 3))", 15), None);
    }
}
