//! The top-level statements of a `.mi` file: `verbose`, `link`, `$include`, `$ifdef`-free
//! scene elements (each handed to its block reader, `incremental` before one replacing the
//! element of that name defined earlier) and `render`.
//!
//! `link "base.so"` (and `physics`, `contour`) names a library whose shaders are built in,
//! as does each of the tutorial's libraries (`myLight.so`, … : [`super::tutorial`]);
//! any other library is native code that cannot be linked (a located warning). `$include`
//! is [`super::include`]'s: here at the top level, inside blocks spliced in by the cursor.

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

/// The top-level statements.
pub const STATEMENTS: &[&str] = &[
    "verbose",
    "link",
    "$include",
    "incremental",
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

/// The definitions `incremental` may stand before (seed 000: "the next options, camera,
/// texture, light, material, object, instance, or instance group definition"; and named
/// shaders).
const INCREMENTAL: &[&str] = &[
    "options",
    "camera",
    "light",
    "material",
    "shader",
    "object",
    "instance",
    "instgroup",
    "color",
    "scalar",
    "vector",
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
    /// The files being read around the one being read, outermost first (an include of one
    /// of them is a cycle).
    reading: Vec<std::path::PathBuf>,
    /// Every `$include` file read, in reading order.
    pub included: Vec<std::path::PathBuf>,
    /// Whether the definition being read follows `incremental`.
    incremental: bool,
    /// The element the definition being read changes (set by [`Self::define`]; `None`
    /// for a fresh definition).
    pub earlier: Option<super::incremental::Earlier>,
    /// The tokens of each statement block, by element name, for `incremental`.
    pub bodies: std::collections::HashMap<String, super::incremental::Body>,
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
            incremental: false,
            earlier: None,
            bodies: Default::default(),
        }
    }

    /// Reads one file (inside the files of `reading`, which include it).
    pub fn read_file(&mut self, path: &Path, bytes: &[u8]) {
        let Ok(text) = std::str::from_utf8(bytes) else {
            self.problems.push(LocatedProblem {
                file: path.to_path_buf(),
                problem: Problem::error(Default::default(), "the file is not UTF-8 text"),
            });
            return;
        };
        let (toks, lex_errors) = tokens(text);
        let mut c = Cursor::new(path.to_path_buf(), toks);
        c.outer = self.reading.clone();
        c.lex_errors(lex_errors);
        while let Some(t) = c.advance() {
            self.statement(&mut c, t);
        }
        self.included.extend(c.spliced().cloned());
        self.problems.extend(c.take_problems());
        // An incremental definition reads the earlier one's tokens again: their problems
        // were reported when first read.
        let mut seen = std::collections::HashSet::new();
        self.problems.retain(|p| seen.insert(p.to_string()));
    }

    /// Records that element `name` is defined at `pos`; reports a second definition. After
    /// `incremental` the name must be defined already, and the earlier element is
    /// forgotten, what it was kept in [`Self::earlier`]: the definition being read starts
    /// from it and replaces it. True when the definition is to be kept.
    pub fn define(&mut self, c: &mut Cursor, name: &str, pos: super::super::located::Pos) -> bool {
        self.earlier = None;
        if std::mem::take(&mut self.incremental) {
            if self.defined.contains_key(name) {
                self.earlier = Some(super::incremental::Earlier {
                    body: self.bodies.remove(name),
                    object: self
                        .raw
                        .objects
                        .iter()
                        .find(|(n, _)| n == name)
                        .map(|(_, o)| o.clone()),
                    instance: self
                        .raw
                        .instances
                        .iter()
                        .find(|(n, _)| n == name)
                        .map(|(_, i)| i.clone()),
                });
                self.raw.forget(name);
            } else {
                let mut p = Problem::error(
                    pos,
                    format!("incremental \"{name}\": no element \"{name}\" is defined before"),
                );
                p = match closest(name, self.defined.keys().map(String::as_str)) {
                    Some(s) => p.with_help(format!("did you mean \"{s}\"?")),
                    None => p.with_help(
                        "incremental changes an element defined earlier; leave it out to define a new one",
                    ),
                };
                c.report(p);
            }
            self.defined.insert(name.to_string(), c.located(pos));
            return true;
        }
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

    fn statement(&mut self, c: &mut Cursor, t: Token) {
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
            "$include" => self.include(c),
            "incremental" => self.incremental(c, t.pos),
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
                resynchronise(c);
            }
        }
    }

    /// `incremental` before a definition: the definition replaces the element of that name
    /// defined earlier (each block's `define` takes the flag).
    fn incremental(&mut self, c: &mut Cursor, pos: super::super::located::Pos) {
        let next = match c.peek() {
            Some(Token {
                tok: Tok::Word(w), ..
            }) if INCREMENTAL.contains(&w.as_str()) => c.advance(),
            _ => None,
        };
        let Some(next) = next else {
            let found = c
                .peek()
                .map_or("the end of the file".into(), |t| t.tok.describe());
            let at = c.peek().map_or(pos, |t| t.pos);
            let mut p = Problem::error(
                at,
                format!("expected a definition after incremental, found {found}"),
            );
            if let Some(Token {
                tok: Tok::Word(w), ..
            }) = c.peek()
            {
                if let Some(s) = closest(w, INCREMENTAL.iter().copied()) {
                    p = p.with_help(format!("did you mean \"{s}\"?"));
                }
                c.advance();
                resynchronise(c);
            }
            c.report(p);
            return;
        };
        self.incremental = true;
        self.statement(c, next);
        self.incremental = false;
    }

    /// `$include` at the top level: reads the file in place (its statements, then the
    /// including file's next ones).
    fn include(&mut self, c: &mut Cursor) {
        let chain = c.chain();
        let Some((file, bytes)) = super::include::target(c, &chain) else {
            return;
        };
        self.included.push(file.clone());
        let outer = std::mem::replace(&mut self.reading, chain);
        self.read_file(&file, &bytes);
        self.reading = outer;
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

/// Error recovery: skips to the next statement keyword.
fn resynchronise(c: &mut Cursor) {
    while c
        .peek()
        .is_some_and(|t| !matches!(&t.tok, Tok::Word(w) if STATEMENTS.contains(&w.as_str())))
    {
        c.advance();
    }
}

/// `"/usr/lib/base.so"` → `base`; `<physics.mi>` → `physics`.
pub fn library_stem(lib: &str) -> String {
    let base = lib.rsplit(['/', '\\']).next().unwrap_or(lib);
    base.split('.').next().unwrap_or(base).to_ascii_lowercase()
}
