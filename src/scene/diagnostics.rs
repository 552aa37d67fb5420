//! Collecting scene diagnostics: [`Sources`] holds every loaded scene file with its
//! [`SourceMap`] and collects errors and warnings as reading and validation find them,
//! each located through the map of the file it is about; [`Sources::finish`] orders the
//! errors by file (load order) and position. The diagnostics themselves are
//! [`super::message`]'s (re-exported here).

use std::path::{Path, PathBuf};

use super::import::SourceMap;
use super::loaded_images::LoadedImages;
pub use super::message::{Diagnostic, SceneErrors, Severity, SourcePos};
pub use super::suggest::suggestion;
use super::syntax::Syntax;

/// A scene file that was read: its display path and where its values are.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// Path as the user gave it, joined with include-relative parts.
    pub path: PathBuf,
    /// Positions of the values, from the file's reader.
    pub map: SourceMap,
    /// The syntax it is written in (help texts show what to write in it).
    pub syntax: Syntax,
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
    /// The environment maps and displacement images decoded so far, and the budget they
    /// are counted against (set by the loader; unlimited by default).
    pub images: LoadedImages,
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

    /// The syntax file `file` is written in (RON when there is no such file).
    pub fn syntax(&self, file: usize) -> Syntax {
        self.files.get(file).map_or(Syntax::Ron, |f| f.syntax)
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

    /// The scene refused: its errors ([`Sources::finish`]) with the warnings found so far.
    pub fn refuse(self) -> SceneErrors {
        let warnings = self.warnings();
        SceneErrors(self.finish(), warnings)
    }
}
