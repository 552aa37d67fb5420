//! Reading the root scene file and, depth-first, every file it includes.
//!
//! Include paths are relative to the including file. A file reached twice through different
//! include chains (a diamond) is loaded once; a file that includes itself, directly or
//! through others, is an include cycle. Display paths are the user's root path joined with
//! the include strings, never absolutized.

use std::collections::HashSet;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use ron::error::Error as RonError;

use super::desc::{self, SceneDesc};
use super::diagnostics::{from_ron, Diagnostic, SourceFile, Sources};
use super::spans::{Pos, SpanIndex};

/// Deepest include chain followed (guards the stack against absurd chains of distinct files).
const MAX_INCLUDE_DEPTH: usize = 64;

/// Every file read, in load order, with its parsed description (`None` where it failed).
pub struct LoadedFiles {
    /// Files and the errors found while reading and parsing them.
    pub sources: Sources,
    /// Parsed descriptions, parallel to `sources.files`.
    pub scenes: Vec<Option<SceneDesc>>,
}

/// Human text for an I/O error, stable across platforms.
pub fn io_reason(err: &io::Error) -> String {
    match err.kind() {
        io::ErrorKind::NotFound => "file not found".into(),
        io::ErrorKind::PermissionDenied => "permission denied".into(),
        io::ErrorKind::IsADirectory => "is a directory".into(),
        _ => err.to_string(),
    }
}

/// Reads `root` (or uses `text` for it) and everything it includes.
pub fn load_files(root: &Path, text: Option<&str>) -> LoadedFiles {
    let mut loader = Loader {
        out: LoadedFiles {
            sources: Sources::default(),
            scenes: Vec::new(),
        },
        stack: Vec::new(),
        seen: HashSet::new(),
    };
    let key = canonical(root);
    match text {
        Some(text) => loader.parse_file(root.to_path_buf(), key, text.to_string()),
        None => match read_text(root) {
            Ok(text) => loader.parse_file(root.to_path_buf(), key, text),
            Err(reason) => {
                let file = loader.register(root.to_path_buf(), SpanIndex::default(), None);
                loader.out.sources.push(
                    file,
                    Pos::default(),
                    Diagnostic {
                        file: root.to_path_buf(),
                        line: 1,
                        column: 1,
                        message: format!("cannot read scene file \"{}\": {reason}", root.display()),
                        help: None,
                    },
                );
            }
        },
    }
    loader.out
}

struct Loader {
    out: LoadedFiles,
    /// Include chain being followed: (canonical key, display path).
    stack: Vec<(PathBuf, PathBuf)>,
    /// Canonical keys of files already loaded.
    seen: HashSet<PathBuf>,
}

fn canonical(path: &Path) -> PathBuf {
    fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

/// Reads a file as UTF-8 text; the error is the reason, for a message.
fn read_text(path: &Path) -> Result<String, String> {
    let bytes = fs::read(path).map_err(|e| io_reason(&e))?;
    String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let valid = String::from_utf8_lossy(valid);
        let line = 1 + valid.matches('\n').count();
        let column = 1 + valid.chars().rev().take_while(|&c| c != '\n').count();
        format!("invalid UTF-8 at line {line}, column {column}")
    })
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

impl Loader {
    fn register(&mut self, path: PathBuf, index: SpanIndex, scene: Option<SceneDesc>) -> usize {
        self.out.sources.files.push(SourceFile { path, index });
        self.out.scenes.push(scene);
        self.out.scenes.len() - 1
    }

    fn parse_file(&mut self, path: PathBuf, key: PathBuf, text: String) {
        self.seen.insert(key.clone());
        let parsed = desc::parse(&text);
        let index = SpanIndex::new(&text);
        let scene = match parsed {
            Ok(scene) => scene,
            Err(err) => {
                let mut d = from_ron(&path, &err);
                (d.line, d.column) = skip_whitespace(&text, d.line, d.column);
                if let RonError::MissingStructField { .. } = err.code {
                    let close = Pos {
                        line: d.line,
                        column: d.column,
                    };
                    if let Some(open) = index.opening_of(close) {
                        (d.line, d.column) = (open.line, open.column);
                    }
                }
                let file = self.register(path.clone(), index, None);
                let pos = Pos {
                    line: d.line,
                    column: d.column,
                };
                self.out.sources.push(file, pos, d);
                return;
            }
        };
        let file = self.register(path.clone(), index, None);
        self.stack.push((key, path.clone()));
        let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
        for (i, include) in scene.include.iter().enumerate() {
            self.include(file, i, &dir.join(include));
        }
        self.stack.pop();
        self.out.scenes[file] = Some(scene);
    }

    fn include(&mut self, from: usize, i: usize, path: &Path) {
        let at = format!("include[{i}]");
        let key = canonical(path);
        if let Some(start) = self.stack.iter().position(|(k, _)| *k == key) {
            let mut chain: Vec<String> = self.stack[start..]
                .iter()
                .map(|(_, p)| p.display().to_string())
                .collect();
            chain.push(path.display().to_string());
            self.out.sources.error(
                from,
                &at,
                format!("include cycle: {}", chain.join(" -> ")),
                Some("a file may not include itself, directly or through other files".into()),
            );
            return;
        }
        if self.seen.contains(&key) {
            return;
        }
        if self.stack.len() >= MAX_INCLUDE_DEPTH {
            self.out.sources.error(
                from,
                &at,
                format!("includes nested deeper than {MAX_INCLUDE_DEPTH} files"),
                None,
            );
            return;
        }
        match read_text(path) {
            Ok(text) => self.parse_file(path.to_path_buf(), key, text),
            Err(reason) => self.out.sources.error(
                from,
                &at,
                format!("cannot read include file \"{}\": {reason}", path.display()),
                None,
            ),
        }
    }
}
