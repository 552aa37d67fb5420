//! Reading the root scene file and, depth-first, every file it includes.
//!
//! Each file is read through the reader seam ([`super::import`]): its format is chosen by
//! its extension, and its reader's errors and warnings are recorded in [`Sources`] with the
//! file's [`super::import::SourceMap`].
//!
//! Include paths are relative to the including file. A file reached twice through different
//! include chains (a diamond) is loaded once; a file that includes itself, directly or
//! through others, is an include cycle. Display paths are the user's root path joined with
//! the include strings, never absolutized.

use std::collections::HashSet;
use std::fs;
use std::path::{Path, PathBuf};

use super::desc::SceneDesc;
use super::diagnostics::{Diagnostic, SourceFile, Sources};
use super::import::{self, SourceMap, SourcePos};
pub use super::message::io_reason;
use super::syntax::Syntax;
use crate::hash::Fnv64;
use crate::limits::{read_file, MAX_SCENE_FILE_BYTES};

/// Deepest include chain followed (guards the stack against absurd chains of distinct files).
const MAX_INCLUDE_DEPTH: usize = 64;

/// Every file read, in load order, with its parsed description (`None` where it failed).
pub struct LoadedFiles {
    /// Files and the errors found while reading and parsing them.
    pub sources: Sources,
    /// Parsed descriptions, parallel to `sources.files`.
    pub scenes: Vec<Option<SceneDesc>>,
    /// FNV-1a over the bytes of every scene file read, in load order, including the files
    /// the readers read themselves (RIB archives, `.mi` includes).
    pub content_hash: Fnv64,
    /// Files the readers read themselves (RIB archives, `.mi` includes), in load order.
    pub read_files: Vec<PathBuf>,
}

/// Reads `root` (or uses `text` for it) and everything it includes, each file with the
/// reader its extension names in `formats` (the loader passes [`import::FORMATS`]).
pub fn load_files(root: &Path, text: Option<&str>, formats: &[import::Format]) -> LoadedFiles {
    let mut loader = Loader {
        formats,
        out: LoadedFiles {
            sources: Sources::default(),
            scenes: Vec::new(),
            content_hash: Fnv64::default(),
            read_files: Vec::new(),
        },
        stack: Vec::new(),
        seen: HashSet::new(),
    };
    let key = canonical(root);
    let failed = |loader: &mut Loader<'_>, message: String, help: Option<String>| {
        let file = loader.register(SourceMap::empty(root), Syntax::default(), None);
        let at = SourcePos::start(root);
        let d = Diagnostic::at(at.clone(), message, help);
        loader.out.sources.push(file, at, d);
    };
    let format = match import::reader_for(formats, root) {
        Ok(format) => format,
        Err((reason, help)) => {
            failed(&mut loader, reason, Some(help));
            return loader.out;
        }
    };
    let bytes = match text {
        Some(text) => Ok(text.as_bytes().to_vec()),
        None => read_file(root, MAX_SCENE_FILE_BYTES, "scene file").map_err(|e| io_reason(&e)),
    };
    match bytes {
        Ok(bytes) => loader.read_file(format, root.to_path_buf(), key, &bytes),
        Err(reason) => failed(
            &mut loader,
            format!("cannot read scene file \"{}\": {reason}", root.display()),
            None,
        ),
    }
    loader.out
}

struct Loader<'f> {
    formats: &'f [import::Format],
    out: LoadedFiles,
    /// Include chain being followed: (canonical key, display path).
    stack: Vec<(PathBuf, PathBuf)>,
    /// Canonical keys of files already loaded.
    seen: HashSet<PathBuf>,
}

fn canonical(path: &Path) -> PathBuf {
    fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

impl Loader<'_> {
    fn register(&mut self, map: SourceMap, syntax: Syntax, scene: Option<SceneDesc>) -> usize {
        let path = map.file().to_path_buf();
        self.out
            .sources
            .files
            .push(SourceFile { path, map, syntax });
        self.out.scenes.push(scene);
        self.out.scenes.len() - 1
    }

    /// Reads one file with its format's reader, then follows its includes.
    fn read_file(&mut self, format: &import::Format, path: PathBuf, key: PathBuf, bytes: &[u8]) {
        self.seen.insert(key.clone());
        self.out.content_hash.bytes(bytes);
        let read = match (format.read)(&path, bytes) {
            Ok(read) => read,
            Err(failure) => {
                let file = self.register(SourceMap::empty(&path), format.syntax, None);
                for d in failure.errors {
                    self.out.sources.push(file, d.pos(), d);
                }
                for w in failure.warnings {
                    self.out.sources.push_warning(file, w);
                }
                return;
            }
        };
        let file = self.register(read.map, format.syntax, None);
        // Files the reader read itself (RIB archives, `.mi` includes) are part of the scene's
        // content: an edited archive must change the farm's scene hash.
        for extra in &read.read_files {
            if let Ok(extra_bytes) = read_file(extra, MAX_SCENE_FILE_BYTES, "scene file") {
                self.out.content_hash.bytes(&extra_bytes);
            }
        }
        self.out.read_files.extend(read.read_files);
        for w in read.warnings {
            self.out.sources.push_warning(file, w);
        }
        let mut scene = read.desc;
        if !self.stack.is_empty() && format.name == import::gltf_scene::FORMAT_NAME {
            import::gltf_scene::as_include(&mut scene);
        }
        self.stack.push((key, path.clone()));
        let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
        for (i, include) in scene.include.iter().enumerate() {
            self.include(file, i, include, &dir.join(include));
        }
        self.stack.pop();
        self.out.scenes[file] = Some(scene);
    }

    /// Follows include `i` of file `from`, written `written` and resolved to `path`.
    fn include(&mut self, from: usize, i: usize, written: &str, path: &Path) {
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
        let cannot_read =
            |reason: String| format!("cannot read include file \"{}\": {reason}", path.display());
        let format = match import::reader_for(self.formats, path) {
            Ok(format) => format,
            Err((reason, help)) => {
                let message = cannot_read(reason);
                self.out.sources.error(from, &at, message, Some(help));
                return;
            }
        };
        match read_file(path, MAX_SCENE_FILE_BYTES, "scene file") {
            Ok(bytes) => self.read_file(format, path.to_path_buf(), key, &bytes),
            Err(e) => {
                let message = cannot_read(io_reason(&e));
                let naming = &self.out.sources.files[from].path;
                let help = super::missing_file::help_if_missing(written, path, naming);
                self.out.sources.error(from, &at, message, help);
            }
        }
    }
}
