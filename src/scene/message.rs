//! Scene diagnostics as the user sees them, the same for every scene format:
//! `file:line:col: error: message` (or `warning:`) plus a `help:` line, and the
//! [`SourcePos`] they are located at.
//!
//! A leaf: it imports nothing else from the scene loader, so the reader seam
//! (`scene::import`) and the collector (`scene::diagnostics`) both build on it.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::components::SourceLink;

/// Where a value was written: the file as the user named it, 1-based line and column (chars).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct SourcePos {
    /// File as the user named it (joined with include-relative parts, never absolutized).
    pub file: PathBuf,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, counting characters.
    pub column: usize,
}

impl SourcePos {
    /// Line 1, column 1 of `file`: where file-level problems are reported.
    pub fn start(file: &Path) -> Self {
        Self {
            file: file.to_path_buf(),
            line: 1,
            column: 1,
        }
    }
}

impl fmt::Display for SourcePos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.display(), self.line, self.column)
    }
}

impl From<SourcePos> for SourceLink {
    fn from(p: SourcePos) -> Self {
        SourceLink {
            file: p.file,
            line: p.line,
            column: p.column,
        }
    }
}

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

/// Every problem found in a scene, reported together, ordered by file then position: the
/// errors (`.0`) and the located warnings found before the errors stopped the load (`.1`,
/// each the complete text as printed, `file:line:col: warning: …`). A refused scene's
/// warnings are shown with its errors, as a compiler shows both: an ignored request or an
/// unused value is often the clue to the error.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneErrors(pub Vec<Diagnostic>, pub Vec<String>);

/// The warnings first (in file and position order), then the errors.
impl fmt::Display for SceneErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let errors = self.0.iter().map(|d| d.to_string());
        for (i, line) in self.1.iter().cloned().chain(errors).enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            f.write_str(&line)?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneErrors {}

/// Human text for an I/O error, stable across platforms.
pub fn io_reason(err: &std::io::Error) -> String {
    match err.kind() {
        std::io::ErrorKind::NotFound => "file not found".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        std::io::ErrorKind::IsADirectory => "is a directory".into(),
        _ => err.to_string(),
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
}
