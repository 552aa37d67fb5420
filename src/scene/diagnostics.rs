//! Scene errors as the user sees them: `file:line:col: error: message` plus a `help:` line.
//!
//! [`Sources`] holds every loaded scene file with its position index and collects errors as
//! validation finds them; [`Sources::finish`] orders them by file (load order) and position.
//! [`from_ron`] turns a `ron` syntax or type error into a diagnostic with a suggestion.

use std::fmt;
use std::path::{Path, PathBuf};

use ron::error::{Error as RonError, SpannedError};

use super::spans::{Pos, SpanIndex};
use super::suggest;
use crate::components::SourceLink;

/// One problem found in a scene, located in a file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// File the problem is in, as the user named it (joined with include-relative parts).
    pub file: PathBuf,
    /// 1-based line.
    pub line: usize,
    /// 1-based column (characters).
    pub column: usize,
    /// What is wrong and what was expected.
    pub message: String,
    /// A suggestion (`did you mean "chrome_red"?`).
    pub help: Option<String>,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: error: {}",
            self.file.display(),
            self.line,
            self.column,
            self.message
        )?;
        if let Some(help) = &self.help {
            write!(f, "\n  help: {help}")?;
        }
        Ok(())
    }
}

/// Every problem found in a scene, reported together, ordered by file then position.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneErrors(pub Vec<Diagnostic>);

impl fmt::Display for SceneErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneErrors {}

/// A scene file that parsed: its display path and where its values are.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// Path as the user gave it, joined with include-relative parts.
    pub path: PathBuf,
    /// Positions of the values in the text.
    pub index: SpanIndex,
}

impl SourceFile {
    /// Directory that relative paths in this file are resolved against.
    pub fn dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new(""))
    }
}

/// Loaded files plus the errors found so far.
#[derive(Debug, Default)]
pub struct Sources {
    /// Files in load order (root first, then includes depth-first).
    pub files: Vec<SourceFile>,
    /// Errors with their sort key (file order, position).
    errors: Vec<(usize, Pos, Diagnostic)>,
}

impl Sources {
    /// Position of the value at `path` in file `file` (or of its nearest written parent).
    pub fn pos(&self, file: usize, path: &str) -> Pos {
        self.files
            .get(file)
            .map_or_else(Pos::default, |f| f.index.locate(path))
    }

    /// `file:line:col` of the value at `path`, for help texts.
    pub fn where_is(&self, file: usize, path: &str) -> String {
        let pos = self.pos(file, path);
        format!("{}:{}:{}", self.display(file), pos.line, pos.column)
    }

    /// Provenance of the element at `path`.
    pub fn link(&self, file: usize, path: &str) -> SourceLink {
        let pos = self.pos(file, path);
        SourceLink {
            file: self
                .files
                .get(file)
                .map(|f| f.path.clone())
                .unwrap_or_default(),
            line: pos.line,
            column: pos.column,
        }
    }

    fn display(&self, file: usize) -> String {
        self.files
            .get(file)
            .map(|f| f.path.display().to_string())
            .unwrap_or_default()
    }

    /// Records an error at the value `path` of file `file`.
    pub fn error(
        &mut self,
        file: usize,
        path: &str,
        message: impl Into<String>,
        help: Option<String>,
    ) {
        let pos = self.pos(file, path);
        let diagnostic = Diagnostic {
            file: self
                .files
                .get(file)
                .map(|f| f.path.clone())
                .unwrap_or_default(),
            line: pos.line,
            column: pos.column,
            message: message.into(),
            help,
        };
        self.errors.push((file, pos, diagnostic));
    }

    /// Records a diagnostic located elsewhere (a file that did not parse, an OBJ file), sorted
    /// as if it were at `pos` of file `file`.
    pub fn push(&mut self, file: usize, pos: Pos, diagnostic: Diagnostic) {
        self.errors.push((file, pos, diagnostic));
    }

    /// Whether any error was recorded.
    pub fn has_errors(&self) -> bool {
        !self.errors.is_empty()
    }

    /// The errors ordered by file (load order), then position; ties keep discovery order.
    pub fn finish(mut self) -> Vec<Diagnostic> {
        self.errors.sort_by_key(|(file, pos, _)| (*file, *pos));
        self.errors.into_iter().map(|(_, _, d)| d).collect()
    }
}

/// `"did you mean …?"` for `wrong` among `candidates`, else a list of what is expected.
pub fn suggestion(wrong: &str, candidates: &[&str], what: &str) -> Option<String> {
    if let Some(best) = suggest::closest(wrong, candidates.iter().copied()) {
        return Some(format!("did you mean \"{best}\"?"));
    }
    match candidates.len() {
        0 => Some(format!("no {what} are defined")),
        1..=8 => Some(format!(
            "expected {}",
            suggest::quoted_list(candidates.iter().copied())
        )),
        _ => None,
    }
}

/// A `ron` syntax or type error as a diagnostic in `file`.
pub fn from_ron(file: &Path, err: &SpannedError) -> Diagnostic {
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

fn ron_message(code: &RonError) -> (String, Option<String>) {
    match code {
        RonError::NoSuchStructField {
            expected,
            found,
            outer,
        } => (
            format!("unknown field \"{found}\"{}", in_outer(outer)),
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
            None,
        ),
        RonError::DuplicateStructField { field, outer } => (
            format!("field \"{field}\" is given twice{}", in_outer(outer)),
            None,
        ),
        RonError::ExpectedDifferentStructName { expected, found } => {
            (format!("expected {expected}(…) but found {found}(…)"), None)
        }
        RonError::InvalidValueForType { expected, found } => {
            (format!("expected {expected} but found {found}"), None)
        }
        RonError::ExpectedDifferentLength { expected, found } => {
            let found = match found {
                0 => "no elements".to_string(),
                1 => "one element".to_string(),
                n => format!("{n} elements"),
            };
            (format!("expected {expected} but found {found}"), None)
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
        RonError::TrailingCharacters => (
            "unexpected text after the scene".into(),
            Some("a file holds exactly one `Scene(...)`; check for an extra `)`".into()),
        ),
        other => (lowercase_first(&other.to_string()), None),
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
    fn display_has_help_on_second_line() {
        let d = Diagnostic {
            file: "a/b.ron".into(),
            line: 3,
            column: 7,
            message: "unknown material \"chrom\"".into(),
            help: Some("did you mean \"chrome\"?".into()),
        };
        assert_eq!(
            d.to_string(),
            "a/b.ron:3:7: error: unknown material \"chrom\"\n  help: did you mean \"chrome\"?"
        );
    }

    #[test]
    fn suggestions_fall_back_to_lists() {
        assert_eq!(
            suggestion("colour", &["color", "name"], "fields").as_deref(),
            Some("did you mean \"color\"?")
        );
        assert_eq!(
            suggestion("zzz", &["albedo"], "fields").as_deref(),
            Some("expected \"albedo\"")
        );
        assert_eq!(
            suggestion("zzz", &[], "materials").as_deref(),
            Some("no materials are defined")
        );
    }
}
