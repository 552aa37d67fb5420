//! The top-level statements of a `.mi` file: `verbose`, `link`, `$include`, `$ifdef`-free
//! scene elements (each handed to its block reader) and `render`.
//!
//! `link "base.so"` (and `physics`, `contour`) names a library whose shaders are built in,
//! as does each of the tutorial's libraries (`myLight.so`, … : [`super::tutorial`]);
//! any other library is native code that cannot be linked (a located warning). `$include
//! <base.mi>` (and the other built-in libraries' declarations) needs nothing; another
//! `<library.mi>` is a warning; `$include "file.mi"` reads that file relative to the
//! including one, at most 16 levels deep.

use std::path::Path;

use super::super::located::{Located, LocatedProblem, Problem};
use super::cursor::Cursor;
use super::lexer::{tokens, Tok, Token};
use super::model::{RawRender, RawScene};
use super::{blocks, object};
use crate::scene::suggest::closest;

/// Libraries whose shaders are built in.
pub const BUILT_IN_LIBRARIES: &[&str] = &["base", "physics", "contour"];

/// The help of a `link` to a library that is not built in: a did-you-mean when the stem is
/// close to a built-in one, and the list of what is built in.
fn link_help(stem: &str) -> String {
    let tutorial = super::tutorial::library_names();
    // Stems are compared in lower case, as `link` matches them.
    let known: Vec<(String, &str)> = BUILT_IN_LIBRARIES
        .iter()
        .copied()
        .chain(tutorial.iter().copied())
        .map(|n| (n.to_ascii_lowercase(), n))
        .collect();
    let guess = closest(stem, known.iter().map(|(lower, _)| lower.as_str()))
        .and_then(|g| known.iter().find(|(lower, _)| lower == g))
        .map(|(_, n)| format!("did you mean \"{n}.so\"? "))
        .unwrap_or_default();
    format!(
        "{guess}built in: the base, physics and contour libraries and the tutorial's {}",
        tutorial
            .iter()
            .map(|n| format!("{n}.so"))
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// The tutorial's displacement library (seed 001, §4.4, its C source printed there):
/// `link "myDisplacement.so"` makes its one shader, `myDisplacement ("factor" f)` =
/// `0.01 · sin(u · f · π)` along the normal, available as a `displace` shader.
pub const TUTORIAL_DISPLACEMENT: &str = "myDisplacement";

/// Deepest `$include` nesting.
const MAX_INCLUDE_DEPTH: usize = 16;

/// The top-level statements.
pub const STATEMENTS: &[&str] = &[
    "verbose",
    "link",
    "$include",
    "options",
    "camera",
    "light",
    "material",
    "declare",
    "shader",
    "object",
    "instance",
    "instgroup",
    "render",
];

/// Reads files statement by statement into a [`RawScene`].
#[derive(Debug)]
pub struct Reader {
    /// The root file (where file-level problems are reported).
    pub root: Located,
    /// What was read.
    pub raw: RawScene,
    /// Every problem, in reading order.
    pub problems: Vec<LocatedProblem>,
    /// Where each element name was first defined (also for elements that failed, so
    /// references to them are not reported a second time).
    pub defined: std::collections::HashMap<String, Located>,
    /// The files being read, outermost first (an include of one of them is a cycle).
    reading: Vec<std::path::PathBuf>,
    /// Every `$include` file read, in reading order.
    pub included: Vec<std::path::PathBuf>,
}

impl Reader {
    /// A reader of the scene whose root file is `path`.
    pub fn new(path: &Path) -> Self {
        Self {
            root: Located {
                file: path.to_path_buf(),
                pos: Default::default(),
            },
            raw: RawScene::default(),
            problems: Vec::new(),
            defined: Default::default(),
            reading: Vec::new(),
            included: Vec::new(),
        }
    }

    /// Reads one file (`depth` levels of `$include` down).
    pub fn read_file(&mut self, path: &Path, bytes: &[u8], depth: usize) {
        let Ok(text) = std::str::from_utf8(bytes) else {
            self.problems.push(LocatedProblem {
                file: path.to_path_buf(),
                problem: Problem::error(Default::default(), "the file is not UTF-8 text"),
            });
            return;
        };
        let (toks, lex_errors) = tokens(text);
        let mut c = Cursor::new(path.to_path_buf(), toks);
        for e in lex_errors {
            c.error(e.pos, e.message);
        }
        while let Some(t) = c.advance() {
            self.statement(&mut c, t, depth);
        }
        let mut problems = std::mem::take(&mut c.problems);
        problems.sort_by_key(|p| p.problem.pos);
        self.problems.extend(problems);
    }

    /// Records that element `name` is defined at `pos`; reports a second definition.
    pub fn define(&mut self, c: &mut Cursor, name: &str, pos: super::super::located::Pos) -> bool {
        if let Some(first) = self.defined.get(name) {
            let help = format!(
                "the first is at {}:{}:{}",
                first.file.display(),
                first.pos.line,
                first.pos.column
            );
            c.report(Problem::error(pos, format!("\"{name}\" is defined twice")).with_help(help));
            return false;
        }
        self.defined.insert(name.to_string(), c.located(pos));
        true
    }

    fn statement(&mut self, c: &mut Cursor, t: Token, depth: usize) {
        let word = match &t.tok {
            Tok::Word(w) => w.clone(),
            other => {
                c.error(
                    t.pos,
                    format!("expected a statement, found {}", other.describe()),
                );
                return;
            }
        };
        match word.as_str() {
            "verbose" => {
                c.skip_arguments();
            }
            "link" => {
                if let Some((lib, pos)) = c.string("the library of link") {
                    let stem = library_stem(&lib);
                    if let Some(shader) = super::tutorial::library(&stem) {
                        self.raw.linked.push(shader.to_string());
                    } else if !BUILT_IN_LIBRARIES.contains(&stem.as_str()) {
                        c.report(
                            Problem::warning(
                                pos,
                                format!("native shader library \"{lib}\" cannot be linked; its shaders are unavailable"),
                            )
                            .with_help(link_help(&stem)),
                        );
                    }
                }
            }
            "$include" => self.include(c, depth),
            "options" => blocks::options(self, c, t.pos),
            "camera" => blocks::camera(self, c, t.pos),
            "light" => blocks::light(self, c, t.pos),
            "material" => blocks::material(self, c, t.pos),
            "declare" => blocks::declare(self, c, t.pos),
            "shader" => blocks::named_shader(self, c),
            "object" => object::object(self, c, t.pos),
            "instance" => object::instance(self, c, t.pos),
            "instgroup" => object::instgroup(self, c, t.pos),
            "render" => self.render(c, t.pos),
            w if super::cursor::TEXTURE_TYPES.contains(&w) && c.at_word("texture") => {
                blocks::texture(self, c)
            }
            other => {
                let mut p = Problem::error(t.pos, format!("unknown statement \"{other}\""));
                if let Some(s) = closest(other, STATEMENTS.iter().copied()) {
                    p = p.with_help(format!("did you mean \"{s}\"?"));
                }
                c.report(p);
                // Resynchronise at the next statement keyword.
                while c.peek().is_some_and(
                    |t| !matches!(&t.tok, Tok::Word(w) if STATEMENTS.contains(&w.as_str())),
                ) {
                    c.advance();
                }
            }
        }
    }

    fn include(&mut self, c: &mut Cursor, depth: usize) {
        let Some(t) = c.advance() else {
            c.error(
                c.pos(),
                "expected a file after $include, found the end of the file",
            );
            return;
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
            }
            Tok::Str(name) => {
                let file = c.file.parent().unwrap_or(Path::new("")).join(&name);
                if depth + 1 > MAX_INCLUDE_DEPTH {
                    c.error(t.pos, format!("includes nest deeper than {MAX_INCLUDE_DEPTH} files (an include cycle?)"));
                    return;
                }
                if self.reading.contains(&file) || file == c.file {
                    c.error(t.pos, format!("\"{}\" includes itself", file.display()));
                    return;
                }
                let read = crate::limits::read_file(
                    &file,
                    crate::limits::MAX_SCENE_FILE_BYTES,
                    "scene file",
                );
                match read {
                    Ok(bytes) => {
                        self.included.push(file.clone());
                        self.reading.push(c.file.clone());
                        self.read_file(&file, &bytes, depth + 1);
                        self.reading.pop();
                    }
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
                    }
                }
            }
            other => c.error(
                t.pos,
                format!(
                    "expected a file name or <library> after $include, found {}",
                    other.describe()
                ),
            ),
        }
    }

    fn render(&mut self, c: &mut Cursor, pos: super::super::located::Pos) {
        let Some(root) = c.string("the root instance group of render") else {
            return;
        };
        let Some(camera) = c.string("the camera instance of render") else {
            return;
        };
        let Some(options) = c.string("the options of render") else {
            return;
        };
        if let Some(first) = &self.raw.render {
            let help = format!(
                "the first is at {}:{}",
                first.at.pos.line, first.at.pos.column
            );
            c.report(Problem::error(pos, "a second render statement").with_help(help));
            return;
        }
        let at = |p| c.located(p);
        self.raw.render = Some(RawRender {
            at: at(pos),
            root: (root.0, at(root.1)),
            camera: (camera.0, at(camera.1)),
            options: (options.0, at(options.1)),
        });
    }
}

/// `"/usr/lib/base.so"` → `base`; `<physics.mi>` → `physics`.
pub fn library_stem(lib: &str) -> String {
    let base = lib.rsplit(['/', '\\']).next().unwrap_or(lib);
    base.split('.').next().unwrap_or(base).to_ascii_lowercase()
}
