//! Scene diagnostics as the user sees them: `file:line:col: error: message` (or
//! `warning:`) plus a `help:` line, the same for every scene format.
//!
//! [`Sources`] holds every loaded scene file with its [`SourceMap`] and collects errors and
//! warnings as reading and validation find them, each located through the map of the file
//! it is about; [`Sources::finish`] orders the errors by file (load order) and position.

use std::fmt;
use std::path::{Path, PathBuf};

use super::import::{SourceMap, SourcePos};
use super::suggest;

/// How bad a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// The scene is refused.
    Error,
    /// The scene loads; something was ignored or changed.
    Warning,
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
        })
    }
}

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

impl Diagnostic {
    /// A diagnostic at `pos`.
    pub fn at(pos: SourcePos, message: impl Into<String>, help: Option<String>) -> Self {
        Self {
            file: pos.file,
            line: pos.line,
            column: pos.column,
            message: message.into(),
            help,
        }
    }

    /// Where it is.
    pub fn pos(&self) -> SourcePos {
        SourcePos {
            file: self.file.clone(),
            line: self.line,
            column: self.column,
        }
    }

    /// The text printed for it with `severity`: `file:line:col: warning: message`.
    pub fn with_severity(&self, severity: Severity) -> Shown<'_> {
        Shown {
            diagnostic: self,
            severity,
        }
    }
}

/// Shows a diagnostic as an error (what a scene refused for prints).
impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.with_severity(Severity::Error).fmt(f)
    }
}

/// A diagnostic with its severity, for printing (see [`Diagnostic::with_severity`]).
#[derive(Debug, Clone, Copy)]
pub struct Shown<'d> {
    diagnostic: &'d Diagnostic,
    severity: Severity,
}

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let d = self.diagnostic;
        write!(
            f,
            "{}:{}:{}: {}: {}",
            d.file.display(),
            d.line,
            d.column,
            self.severity,
            d.message
        )?;
        if let Some(help) = &d.help {
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

/// A scene file that was read: its display path and where its values are.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// Path as the user gave it, joined with include-relative parts.
    pub path: PathBuf,
    /// Positions of the values, from the file's reader.
    pub map: SourceMap,
}

impl SourceFile {
    /// Directory that relative paths in this file are resolved against.
    pub fn dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new(""))
    }
}

/// A recorded diagnostic with its sort key: file index (load order), line, column.
type Keyed = ((usize, usize, usize), Diagnostic);

/// Loaded files plus the errors and warnings found so far.
#[derive(Debug, Default)]
pub struct Sources {
    /// Files in load order (root first, then includes depth-first).
    pub files: Vec<SourceFile>,
    errors: Vec<Keyed>,
    warnings: Vec<Keyed>,
}

impl Sources {
    /// Position of the value at `path` in file `file` (or of its nearest written parent).
    pub fn pos(&self, file: usize, path: &str) -> SourcePos {
        self.files
            .get(file)
            .map_or_else(|| SourcePos::start(Path::new("")), |f| f.map.locate(path))
    }

    /// `file:line:col` of the value at `path`, for help texts.
    pub fn where_is(&self, file: usize, path: &str) -> String {
        self.pos(file, path).to_string()
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
        self.push(file, pos.clone(), Diagnostic::at(pos, message, help));
    }

    /// Records an error located elsewhere (a file that did not parse, an OBJ file), sorted
    /// as if it were at `pos` of file `file`.
    pub fn push(&mut self, file: usize, pos: SourcePos, diagnostic: Diagnostic) {
        self.errors.push(((file, pos.line, pos.column), diagnostic));
    }

    /// Records a located warning about file `file` (sorted at its own position).
    pub fn push_warning(&mut self, file: usize, diagnostic: Diagnostic) {
        let key = (file, diagnostic.line, diagnostic.column);
        self.warnings.push((key, diagnostic));
    }

    /// Whether any error was recorded.
    pub fn has_errors(&self) -> bool {
        !self.errors.is_empty()
    }

    /// The warnings ordered like the errors, printed `file:line:col: warning: …`.
    pub fn warnings(&self) -> Vec<String> {
        let mut sorted: Vec<&Keyed> = self.warnings.iter().collect();
        sorted.sort_by_key(|(key, _)| *key);
        sorted
            .into_iter()
            .map(|(_, d)| d.with_severity(Severity::Warning).to_string())
            .collect()
    }

    /// The errors ordered by file (load order), then position; ties keep discovery order.
    pub fn finish(mut self) -> Vec<Diagnostic> {
        self.errors.sort_by_key(|(key, _)| *key);
        self.errors.into_iter().map(|(_, d)| d).collect()
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
        // Long lists too (Camera, Options): a user who typed an unknown name needs them.
        _ => Some(format!(
            "expected one of {}",
            suggest::quoted_list(candidates.iter().copied())
        )),
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
        assert_eq!(
            d.with_severity(Severity::Warning).to_string(),
            "a/b.ron:3:7: warning: unknown material \"chrom\"\n  help: did you mean \"chrome\"?"
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
