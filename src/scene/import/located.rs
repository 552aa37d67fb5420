//! What the two text readers (RIB, `.mi`) share: 1-based positions, problems located in
//! the file being read, a token and a lexical error at a position, the character cursor
//! their lexers walk with, and the step from a reader's located result to a [`ReadScene`].

use std::path::{Path, PathBuf};

use super::{PathTable, ReadFailure, ReadScene, SourcePos};
use crate::scene::desc::SceneDesc;
use crate::scene::message::Diagnostic;

/// A 1-based line and column (columns count characters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Pos {
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

impl Default for Pos {
    fn default() -> Self {
        Self { line: 1, column: 1 }
    }
}

/// A problem found while reading, located in the file being read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// Where.
    pub pos: Pos,
    /// What.
    pub message: String,
    /// A suggestion.
    pub help: Option<String>,
    /// A warning (something ignored) rather than an error.
    pub warning: bool,
}

impl Problem {
    /// An error at `pos`.
    pub fn error(pos: Pos, message: impl Into<String>) -> Self {
        Self {
            pos,
            message: message.into(),
            help: None,
            warning: false,
        }
    }

    /// A warning at `pos`.
    pub fn warning(pos: Pos, message: impl Into<String>) -> Self {
        Self {
            warning: true,
            ..Self::error(pos, message)
        }
    }

    /// The same problem with a `help:` line.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }
}

/// A position in one of the files read (the root, a RIB `ReadArchive`, a `.mi` `$include`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Located {
    /// The file, as the user named it (included files joined to the reading file's folder).
    pub file: PathBuf,
    /// Line and column.
    pub pos: Pos,
}

/// A problem with its file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LocatedProblem {
    /// The file.
    pub file: PathBuf,
    /// The problem.
    pub problem: Problem,
}

impl std::fmt::Display for LocatedProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = &self.problem;
        write!(
            f,
            "{}:{}:{}: {}: {}",
            self.file.display(),
            p.pos.line,
            p.pos.column,
            if p.warning { "warning" } else { "error" },
            p.message
        )?;
        if let Some(h) = &p.help {
            write!(f, "\n  help: {h}")?;
        }
        Ok(())
    }
}

impl LocatedProblem {
    /// The loader's diagnostic for this problem.
    fn diagnostic(self) -> Diagnostic {
        Diagnostic {
            file: self.file,
            line: self.problem.pos.line,
            column: self.problem.pos.column,
            message: self.problem.message,
            help: self.problem.help,
        }
    }
}

/// A token of a lexer's kind `T` and where its first character is.
#[derive(Debug, Clone, PartialEq)]
pub struct Token<T> {
    /// The token.
    pub tok: T,
    /// Where its first character is.
    pub pos: Pos,
}

/// A lexical error: where and what.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LexError {
    /// Where the offending character is.
    pub pos: Pos,
    /// What is wrong.
    pub message: String,
}

/// A lexer's walk over a text's characters, keeping the position of the next one.
pub struct CharCursor {
    chars: Vec<char>,
    at: usize,
    pos: Pos,
}

impl CharCursor {
    /// At the first character of `text` (line 1, column 1). A UTF-8 byte order mark
    /// (editors on Windows write one) is not part of the text and is skipped, as the RON
    /// reader skips it.
    pub fn new(text: &str) -> Self {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        Self {
            chars: text.chars().collect(),
            at: 0,
            pos: Pos::default(),
        }
    }

    /// The next character, not taken.
    pub fn peek(&self) -> Option<char> {
        self.chars.get(self.at).copied()
    }

    /// Takes the next character (a newline starts the next line).
    pub fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.at += 1;
        if c == '\n' {
            self.pos.line += 1;
            self.pos.column = 1;
        } else {
            self.pos.column += 1;
        }
        Some(c)
    }

    /// Where the next character is.
    pub fn pos(&self) -> Pos {
        self.pos
    }
}

/// What a text reader made of one file, every position with its file.
#[derive(Debug, Clone)]
pub struct LocatedScene {
    /// The description.
    pub desc: SceneDesc,
    /// Where each element and value was written, by description path
    /// (`objects[3].mesh.Sphere.radius`), in the order recorded.
    pub paths: Vec<(String, Located)>,
    /// What was read but not mapped (ignored), located.
    pub warnings: Vec<LocatedProblem>,
    /// The files the reader read itself (RIB `ReadArchive`, `.mi` `$include`; the root file
    /// left out).
    pub read_files: Vec<PathBuf>,
}

/// A text reader's result as the loader takes it: positions in a [`PathTable`], problems
/// as diagnostics.
pub fn read_scene(
    path: &Path,
    read: Result<LocatedScene, Vec<LocatedProblem>>,
) -> Result<ReadScene, ReadFailure> {
    let scene = read.map_err(|problems| {
        let (warnings, errors): (Vec<_>, Vec<_>) =
            problems.into_iter().partition(|p| p.problem.warning);
        ReadFailure {
            errors: errors.into_iter().map(LocatedProblem::diagnostic).collect(),
            warnings: warnings
                .into_iter()
                .map(LocatedProblem::diagnostic)
                .collect(),
        }
    })?;
    let mut table = PathTable::default();
    for (p, at) in scene.paths {
        table.insert(
            p,
            SourcePos {
                file: at.file,
                line: at.pos.line,
                column: at.pos.column,
            },
        );
    }
    Ok(ReadScene {
        desc: scene.desc,
        map: table.into_map(path),
        warnings: scene
            .warnings
            .into_iter()
            .map(LocatedProblem::diagnostic)
            .collect(),
        read_files: scene.read_files,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Columns count characters, not bytes; a newline starts the next line at column 1.
    #[test]
    fn the_cursor_counts_characters_and_lines() {
        let mut c = CharCursor::new("aé\nb");
        let mut seen = Vec::new();
        while let Some(ch) = c.peek() {
            seen.push((ch, c.pos()));
            c.bump();
        }
        let at = |line, column| Pos { line, column };
        assert_eq!(
            seen,
            [
                ('a', at(1, 1)),
                ('é', at(1, 2)),
                ('\n', at(1, 3)),
                ('b', at(2, 1))
            ]
        );
        assert_eq!((c.bump(), c.pos()), (None, at(2, 2)));
    }

    #[test]
    fn a_byte_order_mark_is_skipped() {
        let c = CharCursor::new("\u{feff}Sphere");
        assert_eq!((c.peek(), c.pos()), (Some('S'), Pos { line: 1, column: 1 }));
    }
}
