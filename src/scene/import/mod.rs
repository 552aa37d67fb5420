//! The reader seam: one interface between scene file formats and the shared loader.
//!
//! A reader turns the bytes of one file into a [`ReadScene`]: the format-neutral description
//! ([`SceneDesc`], the plain data RON deserialises into), a [`SourceMap`] saying where each
//! element and value was written, and located warnings. Everything after reading —
//! merging, validation, name resolution, the instance DAG, spawning and diagnostics — is
//! shared, so an error found by validation in any format prints the same way:
//! `scene.rib:12:7: error: … \n  help: …`.
//!
//! Owned here:
//! - [`SourcePos`]: where a value was written (file as the user named it, 1-based line and
//!   column in characters).
//! - [`ReadScene`] and [`ReadFn`]: what a reader produces, and its signature. A reader
//!   reports every located error it finds (collected, not first-only).
//! - [`SourceMap`]: positions by description path, with lookup falling back to the nearest
//!   written parent. RON builds its map from the text ([`ron`]); other readers fill a
//!   [`PathTable`] while they parse (`table.insert("objects[3].mesh", pos)`).
//! - [`FORMATS`]: the extension table (`.ron` today; `.rib`, `.mi`, `.gltf`/`.glb` arms are
//!   added by their readers) and [`reader_for`], which picks a reader by extension. An
//!   unknown extension is a located error naming the known ones.
//!
//! Includes listed in `desc.include` are followed by the shared include loader
//! (`scene::include`); a reader with its own inline-include semantics (RIB `ReadArchive`,
//! `.mi` `$include`) may inline them itself and record positions in the included file (a
//! [`SourcePos`] names its own file).
//!
//! Path syntax (what validation asks the map for): `.field` selects a struct field
//! (`objects[3].name`); `.Name` selects a named variant (`objects[3].mesh.Sphere.radius`,
//! where `Sphere` documents the variant); `[i]` selects the i-th item of a list or tuple
//! (`lights[0].color[2]`). The element paths are `options`, `render`, `cameras[i]`,
//! `lights[i]`, `materials[i]`, `objects[i]`, `instances[i]`, `groups[i]`, `phenomena[i]`
//! and `include[i]`; the empty path is the file itself.

pub mod gltf_scene;
pub mod located;
pub mod mi;
pub mod relocate;
pub mod rib;
pub mod ron;
mod ron_brackets;
mod ron_comments;
mod ron_forms;
mod ron_hints;
mod ron_integers;
mod ron_spans;
mod ron_tuples;
mod ron_unclosed;
pub mod to_ron;

use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::desc::SceneDesc;
use super::message::Diagnostic;
pub use super::message::SourcePos;
use super::nodes_desc::NodeDesc;
use super::syntax::Syntax;

/// What one reader produced from one file.
#[derive(Debug)]
pub struct ReadScene {
    /// The format-neutral scene description. Includes listed in `desc.include` are resolved
    /// by the shared include loader.
    pub desc: SceneDesc,
    /// Positions of elements and values by their description path.
    pub map: SourceMap,
    /// Located warnings (`file:line:col: warning: ignored request "Hider"`), never dropped
    /// silently.
    pub warnings: Vec<Diagnostic>,
    /// Other files the reader read itself (RIB `ReadArchive`, `.mi` `$include`): inputs of
    /// the scene, which no output may overwrite.
    pub read_files: Vec<PathBuf>,
}

/// A reader's refusal of one file: every located error, and the located warnings found on the
/// way (shown with the errors: an ignored request is often the clue to an error).
#[derive(Debug, Default)]
pub struct ReadFailure {
    /// The errors, in the reader's order (file, then position).
    pub errors: Vec<Diagnostic>,
    /// The warnings.
    pub warnings: Vec<Diagnostic>,
}

/// Errors alone.
impl From<Vec<Diagnostic>> for ReadFailure {
    fn from(errors: Vec<Diagnostic>) -> Self {
        Self {
            errors,
            warnings: Vec::new(),
        }
    }
}

/// A reader: bytes of one file (its path as the user named it) → [`ReadScene`], or every
/// located problem found.
pub type ReadFn = fn(path: &Path, bytes: &[u8]) -> Result<ReadScene, ReadFailure>;

/// A reader's index of positions, behind a [`SourceMap`].
pub trait PositionIndex: fmt::Debug + Send + Sync {
    /// Position of the value at `path`; if it is not written (a defaulted field, say), of the
    /// deepest value on the path that is. `None` when nothing on the path is recorded, not
    /// even the file itself.
    fn locate(&self, path: &str) -> Option<SourcePos>;

    /// Reads the value at `path` again as a shader-graph node, for an input the description
    /// holds only as untyped data (RON: a node written with all defaults, or a misspelt
    /// one). `None` when the value is not written or the format never leaves inputs untyped;
    /// `Err` carries the value's position (for ordering) and the located problem.
    fn reread_node(&self, path: &str) -> Option<Result<NodeDesc, (SourcePos, Diagnostic)>> {
        let _ = path;
        None
    }
}

/// Where the values of one file were written, by description path.
#[derive(Debug, Clone)]
pub struct SourceMap {
    /// The file as the user named it: where unrecorded paths are reported (line 1, column 1).
    file: PathBuf,
    index: Arc<dyn PositionIndex>,
}

impl SourceMap {
    /// A map over a reader's own index.
    pub fn new(file: &Path, index: impl PositionIndex + 'static) -> Self {
        Self {
            file: file.to_path_buf(),
            index: Arc::new(index),
        }
    }

    /// A map that knows no positions (a file that could not be read): everything is at 1:1.
    pub fn empty(file: &Path) -> Self {
        Self::new(file, PathTable::default())
    }

    /// The file as the user named it.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// Position of the value at `path`, falling back to its nearest written parent and,
    /// failing that, to the start of the file.
    pub fn locate(&self, path: &str) -> SourcePos {
        self.index
            .locate(path)
            .unwrap_or_else(|| SourcePos::start(&self.file))
    }

    /// See [`PositionIndex::reread_node`].
    pub fn reread_node(&self, path: &str) -> Option<Result<NodeDesc, (SourcePos, Diagnostic)>> {
        self.index.reread_node(path)
    }
}

/// Positions recorded by a reader while it parses, for formats that are not RON.
#[derive(Debug, Clone, Default)]
pub struct PathTable {
    entries: HashMap<String, SourcePos>,
}

impl PathTable {
    /// Records that the value at `path` was written at `pos` (a later insert wins).
    pub fn insert(&mut self, path: impl Into<String>, pos: SourcePos) {
        self.entries.insert(path.into(), pos);
    }

    /// The map of file `file` over this table.
    pub fn into_map(self, file: &Path) -> SourceMap {
        SourceMap::new(file, self)
    }
}

impl PositionIndex for PathTable {
    fn locate(&self, path: &str) -> Option<SourcePos> {
        let mut at = Some(path);
        while let Some(p) = at {
            if let Some(pos) = self.entries.get(p) {
                return Some(pos.clone());
            }
            at = parent(p);
        }
        None
    }
}

/// The path one step up: `a.b[2]` → `a.b` → `a` → `` → none.
pub fn parent(path: &str) -> Option<&str> {
    if path.is_empty() {
        return None;
    }
    let cut = path.rfind(['.', '[']).unwrap_or(0);
    Some(&path[..cut])
}

/// One scene format: its name and extensions, and its reader.
#[derive(Debug, Clone, Copy)]
pub struct Format {
    /// Name for messages (`RON`).
    pub name: &'static str,
    /// Extensions without the dot, lowercase (`ron`).
    pub extensions: &'static [&'static str],
    /// The reader.
    pub read: ReadFn,
    /// The syntax its files are written in (for help texts).
    pub syntax: Syntax,
}

/// Every scene format, by extension (compared case-insensitively).
pub const FORMATS: &[Format] = &[
    Format {
        name: "RON",
        extensions: &["ron"],
        read: ron::read,
        syntax: Syntax::Ron,
    },
    Format {
        name: "RIB",
        extensions: &["rib"],
        read: rib::read,
        syntax: Syntax::Rib,
    },
    Format {
        name: gltf_scene::FORMAT_NAME,
        extensions: &["gltf", "glb"],
        read: gltf_scene::read,
        syntax: Syntax::Gltf,
    },
    Format {
        name: "mental ray",
        extensions: &["mi"],
        read: mi::read,
        syntax: Syntax::Mi,
    },
];

/// The syntax the scene file at `path` is written in, by its extension as the readers are
/// chosen (RON when none takes it), so that a help shows what to write in that file.
pub fn syntax_of(path: &Path) -> Syntax {
    reader_for(FORMATS, path).map_or_else(|_| Syntax::default(), |f| f.syntax)
}

/// The known extensions as a help text: `known scene formats: .ron`.
fn known_formats(formats: &[Format]) -> String {
    let list: Vec<String> = formats
        .iter()
        .flat_map(|f| f.extensions.iter().map(|e| format!(".{e}")))
        .collect();
    format!("known scene formats: {}", list.join(", "))
}

/// The format of `path` among `formats` (the loader passes [`FORMATS`]), chosen by its
/// extension; else the reason there is none and the help listing the known formats (the
/// caller locates the error: the file itself for the root, the include entry for an
/// include).
pub fn reader_for<'f>(formats: &'f [Format], path: &Path) -> Result<&'f Format, (String, String)> {
    if path.is_dir() {
        return Err((
            "this is a directory, not a scene file".into(),
            format!("give a scene file; {}", known_formats(formats)),
        ));
    }
    let Some(ext) = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
    else {
        return Err((
            "no file extension to choose a scene format by".into(),
            known_formats(formats),
        ));
    };
    formats
        .iter()
        .find(|f| f.extensions.contains(&ext.as_str()))
        .ok_or_else(|| {
            let reason = format!("unknown scene format \".{ext}\"");
            (reason, known_formats(formats))
        })
}

#[cfg(test)]
mod tests;
