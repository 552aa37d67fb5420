//! `$include`: mental ray's include is textual, so it may stand wherever a statement can —
//! at the top level (the statements reader reads the file in place) or inside a block (the
//! cursor splices the file's tokens in where the `$include` was, [`super::cursor::Cursor`]).
//!
//! `$include <base.mi>` (and the other built-in libraries' declarations) needs nothing;
//! another `<library.mi>` is a warning; `$include "file.mi"` names a file relative to the
//! including one. A file already on the include chain is a cycle, and the chain is at most
//! [`MAX_INCLUDE_DEPTH`] files deep; both are errors at the file name, as is a file that
//! cannot be read.

use std::path::{Path, PathBuf};

use super::cursor::Cursor;
use super::lexer::Tok;
use super::statements::{library_stem, BUILT_IN_LIBRARIES};

/// Deepest `$include` nesting.
pub const MAX_INCLUDE_DEPTH: usize = 16;

/// Reads what follows an `$include` (already consumed) at the cursor. `chain` holds the
/// files being read, outermost first, the including file last. Returns the included file
/// and its bytes for `$include "file"`; `None` for a library include (warned where it is
/// not built in) and after an error (reported).
pub fn target(c: &mut Cursor, chain: &[PathBuf]) -> Option<(PathBuf, Vec<u8>)> {
    let Some(t) = c.advance() else {
        c.error(
            c.pos(),
            "expected a file after $include, found the end of the file",
        );
        return None;
    };
    match t.tok {
        Tok::Library(lib) => {
            let stem = library_stem(&lib);
            if !BUILT_IN_LIBRARIES.contains(&stem.as_str())
                && super::tutorial::library(&stem).is_none()
            {
                c.warn(
                    t.pos,
                    format!("library include <{lib}> declares native shaders; not read"),
                );
            }
            None
        }
        Tok::Str(name) => {
            let including = chain.last().map_or(Path::new(""), PathBuf::as_path);
            let file = including.parent().unwrap_or(Path::new("")).join(&name);
            if chain.len() > MAX_INCLUDE_DEPTH {
                c.error(
                    t.pos,
                    format!(
                        "includes nest deeper than {MAX_INCLUDE_DEPTH} files (an include cycle?)"
                    ),
                );
                return None;
            }
            if chain.contains(&file) {
                c.error(t.pos, format!("\"{}\" includes itself", file.display()));
                return None;
            }
            let read =
                crate::limits::read_file(&file, crate::limits::MAX_SCENE_FILE_BYTES, "scene file");
            match read {
                Ok(bytes) => Some((file, bytes)),
                Err(e) => {
                    let why = if e.kind() == std::io::ErrorKind::NotFound {
                        "file not found".to_string()
                    } else {
                        e.to_string()
                    };
                    c.error(
                        t.pos,
                        format!("cannot read include \"{}\": {why}", file.display()),
                    );
                    None
                }
            }
        }
        other => {
            c.error(
                t.pos,
                format!(
                    "expected a file name or <library> after $include, found {}",
                    other.describe()
                ),
            );
            None
        }
    }
}
