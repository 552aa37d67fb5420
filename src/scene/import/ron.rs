//! The RON reader: `.ron` text → [`ReadScene`].
//!
//! Owns everything that knows RON text: parsing with the `ron` crate (with the
//! `implicit_some` extension), turning `ron`'s syntax and type errors into diagnostics with
//! suggestions, and the position index ([`super::ron_spans`]) that locates every value by
//! its path, because `ron` reports positions for its own errors but not for the values it
//! returns. A RON file holds no warnings; `ron` stops at the first syntax error of a file.

use std::path::{Path, PathBuf};

use ron::error::{Error as RonError, SpannedError};

use super::ron_spans::{Pos, SpanIndex};
use super::{PositionIndex, ReadScene, SourceMap, SourcePos};
use crate::scene::desc::SceneDesc;
use crate::scene::message::Diagnostic;
use crate::scene::nodes_desc::NodeDesc;
use crate::scene::suggest::suggestion;

/// Reads one RON scene file (the [`super::ReadFn`] of `.ron`).
pub fn read(path: &Path, bytes: &[u8]) -> Result<ReadScene, super::ReadFailure> {
    let text = std::str::from_utf8(bytes).map_err(|e| vec![not_utf8(path, bytes, &e)])?;
    // A UTF-8 byte order mark (editors on Windows write one) is not part of the scene; the
    // columns of line 1 are then counted as the editor shows them.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let index = SpanIndex::new(text);
    let parsed = parse(text);
    if parsed.is_ok() {
        if let Some(style) = wrong_call_style(path, &index, None) {
            return Err(vec![style].into());
        }
    }
    match parsed {
        Ok(desc) => Ok(ReadScene {
            desc,
            map: SourceMap::new(
                path,
                RonIndex {
                    file: path.to_path_buf(),
                    spans: index,
                },
            ),
            warnings: Vec::new(),
            read_files: Vec::new(),
        }),
        Err(err) => {
            let mut d = from_ron(path, &err);
            (d.line, d.column) = skip_whitespace(text, d.line, d.column);
            let at = Pos {
                line: d.line,
                column: d.column,
            };
            if let Some(style) = wrong_call_style(path, &index, Some(at)) {
                return Err(vec![style].into());
            }
            if let Some(hint) = super::ron_comments::explain(text, at) {
                (d.line, d.column) = (hint.at.line, hint.at.column);
                (d.message, d.help) = (hint.message, Some(hint.help));
                return Err(vec![d].into());
            }
            let before = (d.line, d.column, d.message.clone());
            if let RonError::IntegerOutOfBounds = err.code {
                if let Some((message, help)) =
                    super::ron_integers::out_of_range(text, d.line, d.column)
                {
                    (d.message, d.help) = (message, Some(help));
                }
            }
            if let RonError::ExpectedComma = err.code {
                if let Some((line, column, message, help)) =
                    super::ron_integers::decimal(text, d.line, d.column)
                {
                    (d.line, d.column, d.message, d.help) = (line, column, message, Some(help));
                }
            }
            if let RonError::MissingStructField { .. } = err.code {
                let close = Pos {
                    line: d.line,
                    column: d.column,
                };
                if let Some(open) = index.opening_of(close) {
                    (d.line, d.column) = (open.line, open.column);
                }
            }
            if before == (d.line, d.column, d.message.clone()) {
                let first_error = |t: &str| {
                    parse(t).err().map(|e| {
                        let (line, column) =
                            skip_whitespace(t, e.span.start.line, e.span.start.col);
                        Pos { line, column }
                    })
                };
                let hint = super::ron_tuples::extra_values(text, &err.code, at)
                    .or_else(|| super::ron_unclosed::explain(text, at, first_error))
                    .or_else(|| super::ron_hints::explain(text, &err.code, at));
                if let Some(hint) = hint {
                    (d.line, d.column) = (hint.at.line, hint.at.column);
                    (d.message, d.help) = (hint.message, Some(hint.help));
                }
            }
            Err(vec![d].into())
        }
    }
}

/// The first shader node written with named inputs where it takes them in order
/// (`Channel(input: Uv, channel: 1)`), if it comes before `limit`: `ron` reads it as
/// something else and misnames the problem (`expected comma`, `unknown node "input"`).
fn wrong_call_style(path: &Path, index: &SpanIndex, limit: Option<Pos>) -> Option<Diagnostic> {
    let (at, name) = index.first_with_fields(&super::ron_forms::positional_names())?;
    if limit.is_some_and(|limit| at >= limit) {
        return None;
    }
    let (message, help) = super::ron_forms::named_instead_of_positional(&name)?;
    Some(Diagnostic {
        file: path.to_path_buf(),
        line: at.line,
        column: at.column,
        message,
        help: Some(help),
    })
}

/// How deep values may nest in a RON scene file (parentheses and brackets inside each
/// other): deeper input is refused with this limit instead of overflowing the stack.
pub const MAX_NESTING: usize = 128;

/// Parses a scene description from RON text.
pub fn parse(text: &str) -> Result<SceneDesc, SpannedError> {
    ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .with_recursion_limit(MAX_NESTING)
        .from_str(text)
}

/// Bytes that are not UTF-8, reported where the first bad byte is.
fn not_utf8(path: &Path, bytes: &[u8], e: &std::str::Utf8Error) -> Diagnostic {
    let valid = String::from_utf8_lossy(&bytes[..e.valid_up_to()]);
    let line = 1 + valid.matches('\n').count();
    let column = 1 + valid.chars().rev().take_while(|&c| c != '\n').count();
    Diagnostic {
        file: path.to_path_buf(),
        line,
        column,
        message: "invalid UTF-8".into(),
        help: Some("a RON scene file is UTF-8 text".into()),
    }
}

/// Positions of one RON file's values.
#[derive(Debug)]
struct RonIndex {
    file: PathBuf,
    spans: SpanIndex,
}

impl RonIndex {
    fn at(&self, pos: Pos) -> SourcePos {
        SourcePos {
            file: self.file.clone(),
            line: pos.line,
            column: pos.column,
        }
    }
}

impl PositionIndex for RonIndex {
    fn locate(&self, path: &str) -> Option<SourcePos> {
        Some(self.at(self.spans.locate(path)))
    }

    /// A node written with all defaults (`Fbm()`, `Uv`) parses here; anything else gets
    /// `ron`'s message at the right position inside the value.
    fn reread_node(&self, path: &str) -> Option<Result<NodeDesc, (SourcePos, Diagnostic)>> {
        let (pos, text) = self.spans.text_at(path)?;
        let parse = |t: &str| {
            ron::Options::default()
                .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
                .from_str::<NodeDesc>(t)
        };
        let bare = text.chars().all(|c| c.is_alphanumeric() || c == '_');
        let result = if bare {
            parse(&format!("{text}()")).or_else(|_| parse(&text))
        } else {
            parse(&text)
        };
        Some(result.map_err(|e| {
            let mut d = from_ron(&self.file, &e);
            let at = Pos {
                line: d.line,
                column: d.column,
            };
            let hint = super::ron_hints::positional_call(&text, at).or_else(|| {
                matches!(e.code, RonError::ExpectedIdentifier)
                    .then(|| super::ron_hints::explain(&text, &e.code, at))
                    .flatten()
            });
            if let Some(hint) = hint {
                (d.line, d.column) = (hint.at.line, hint.at.column);
                (d.message, d.help) = (hint.message, Some(hint.help));
            }
            let (line, column) = if d.line <= 1 {
                (pos.line, pos.column + d.column.saturating_sub(1))
            } else {
                (pos.line + d.line - 1, d.column)
            };
            (self.at(pos), Diagnostic { line, column, ..d })
        }))
    }
}

/// The first non-whitespace position at or after `line:column` (ron reports some errors
/// at the blank before the offending value).
fn skip_whitespace(text: &str, line: usize, column: usize) -> (usize, usize) {
    let Some(start) = text.split_inclusive('\n').nth(line.saturating_sub(1)) else {
        return (line, column);
    };
    let offset = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum::<usize>();
    let from = start
        .char_indices()
        .nth(column.saturating_sub(1))
        .map_or(start.len(), |(i, _)| i);
    let (mut line, mut column) = (line, column);
    for c in text[offset + from..].chars() {
        if !c.is_whitespace() {
            return (line, column);
        }
        if c == '\n' {
            line += 1;
            column = 1;
        } else {
            column += 1;
        }
    }
    (line, column)
}

/// A `ron` syntax or type error as a diagnostic in `file`.
fn from_ron(file: &Path, err: &SpannedError) -> Diagnostic {
    let (message, help) = ron_message(&err.code);
    Diagnostic {
        file: file.to_path_buf(),
        line: err.span.start.line,
        column: err.span.start.col,
        message,
        help,
    }
}

fn in_outer(outer: &Option<String>) -> String {
    outer
        .as_ref()
        .map(|o| format!(" in {o}"))
        .unwrap_or_default()
}

/// The name of a value that a hand-written visitor reads (whose errors `ron` names after
/// the enclosing struct), known by its field list.
fn hand_written_name(expected: &[&str]) -> Option<String> {
    use crate::scene::desc_camera::{ADAPTIVE_FIELDS, ADAPTIVE_NAME};
    (expected == ADAPTIVE_FIELDS).then(|| ADAPTIVE_NAME.to_string())
}

fn ron_message(code: &RonError) -> (String, Option<String>) {
    match code {
        RonError::NoSuchStructField {
            expected,
            found,
            outer,
        } => (
            format!(
                "unknown field \"{found}\"{}",
                in_outer(&hand_written_name(expected).or(outer.clone()))
            ),
            suggestion(found, expected, "fields"),
        ),
        RonError::NoSuchEnumVariant {
            expected,
            found,
            outer,
        } => (
            format!(
                "unknown variant \"{found}\"{}",
                outer
                    .as_ref()
                    .map(|o| format!(" of {o}"))
                    .unwrap_or_default()
            ),
            suggestion(found, expected, "variants"),
        ),
        RonError::MissingStructField { field, outer } => (
            format!("missing field \"{field}\"{}", in_outer(outer)),
            Some(format!(
                "add `{field}: …`; docs/scene-format.md lists the fields and their defaults"
            )),
        ),
        RonError::DuplicateStructField { field, outer } => (
            format!("field \"{field}\" is given twice{}", in_outer(outer)),
            Some(format!("keep one `{field}: …`")),
        ),
        RonError::ExpectedDifferentStructName { expected, found } => (
            format!("expected {expected}(…) but found {found}(…)"),
            Some(format!("write `{expected}(…)` here")),
        ),
        RonError::InvalidValueForType { expected, found } => (
            format!("expected {expected} but found {found}"),
            Some("docs/scene-format.md gives the type of every field".into()),
        ),
        RonError::ExpectedDifferentLength { expected, found } => {
            let found = match found {
                0 => "no elements".to_string(),
                1 => "one element".to_string(),
                n => format!("{n} elements"),
            };
            (
                format!("expected {expected} but found {found}"),
                Some(match expected.rsplit(' ').next().map(str::parse::<usize>) {
                    Some(Ok(n)) => format!("write exactly {n} values in `(…)`"),
                    _ => format!("write {expected}"),
                }),
            )
        }
        RonError::Message(text) if text.ends_with(crate::scene::unique_keys::GIVEN_TWICE) => {
            (text.clone(), Some("keep one entry for each key".into()))
        }
        RonError::Message(text) => (text.clone(), None),
        RonError::ExpectedComma => (
            "expected comma".into(),
            Some("separate fields and list items with `,`".into()),
        ),
        RonError::Eof => (
            "unexpected end of file".into(),
            Some("a `(` or `[` is not closed".into()),
        ),
        RonError::ExceededRecursionLimit => (
            format!("values nested deeper than {MAX_NESTING} levels"),
            Some(
                "a scene file nests at most that deep: declare inner shader nodes as \
                 phenomena and call them with Graph(…)"
                    .into(),
            ),
        ),
        RonError::TrailingCharacters => (
            "unexpected text after the scene".into(),
            Some("a file holds exactly one `Scene(...)`; check for an extra `)`".into()),
        ),
        RonError::ExpectedStringEnd => (
            "expected end of string".into(),
            Some("close the string with `\"`; write `\\\"` for a quote inside it".into()),
        ),
        other => (
            lowercase_first(&other.to_string()),
            Some(
                match other {
                    RonError::ExpectedFloat => "write a number such as `1.0`",
                    RonError::ExpectedInteger => "write a whole number such as `4`",
                    RonError::ExpectedBoolean => "write `true` or `false`",
                    RonError::ExpectedString => "write text in double quotes, e.g. `\"name\"`",
                    RonError::ExpectedArray => "write a list `[…]` here",
                    RonError::ExpectedArrayEnd => "close the list with `]`",
                    RonError::ExpectedStructLike => "write `(…)` here",
                    RonError::ExpectedStructLikeEnd => "close the `(` with `)`",
                    RonError::ExpectedOption => "write `Some(…)` or `None`",
                    RonError::ExpectedIdentifier => "write a field or variant name here",
                    _ => "docs/scene-format.md shows the syntax of every field",
                }
                .into(),
            ),
        ),
    }
}

fn lowercase_first(text: &str) -> String {
    let mut chars = text.chars();
    match chars.next() {
        Some(c) => c.to_lowercase().chain(chars).collect(),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_located_by_path_with_parent_fallback() {
        let text = "Scene(\n  objects: [\n    (name: \"q\", mesh: Sphere(radius: 2)),\n  ],\n)";
        let read = read(Path::new("a/s.ron"), text.as_bytes()).unwrap();
        let at = |p: &str| read.map.locate(p).to_string();
        assert_eq!(at("objects[0]"), "a/s.ron:3:5");
        assert_eq!(at("objects[0].mesh.Sphere.radius"), "a/s.ron:3:38");
        // `material` is not written: its element's position.
        assert_eq!(at("objects[0].material"), "a/s.ron:3:5");
        assert!(read.warnings.is_empty());
    }

    #[test]
    fn syntax_errors_and_bad_bytes_are_located_in_the_file() {
        let errors =
            read(Path::new("s.ron"), b"Scene(\n  objects: [] cameras: [],\n)").unwrap_err();
        let got: Vec<String> = errors.errors.iter().map(ToString::to_string).collect();
        assert_eq!(
            got,
            ["s.ron:2:14: error: expected comma\n  help: add ',' here"]
        );
        let errors = read(Path::new("s.ron"), b"Scene(\n  // caf\xff\n)").unwrap_err();
        assert_eq!(
            errors.errors[0].to_string(),
            "s.ron:2:9: error: invalid UTF-8\n  help: a RON scene file is UTF-8 text"
        );
    }
}
